//! The HTTP of `footprint serve`: a request head parsed by `httparse` from the first
//! [`MAX_HEAD`] bytes a connection sent, and the answer to it, built in memory (the body is
//! borrowed from the [`Site`]).

use super::{Site, MAX_HEAD};

/// A request's head, as far as the server reads it.
pub(super) struct Head {
    pub(super) method: String,
    pub(super) path: String,
    /// The `Host` headers' values.
    pub(super) hosts: Vec<String>,
    /// HTTP/1.1 (else 1.0).
    pub(super) http11: bool,
    /// `Connection: close` (1.1) or no `Connection: keep-alive` (1.0).
    pub(super) close: bool,
    /// A body follows (`Content-Length` > 0 or `Transfer-Encoding`): the server reads none,
    /// so it closes the connection after answering.
    pub(super) body: bool,
}

/// What the start of a connection's input holds.
pub(super) enum Parsed {
    /// A whole head, and its length in bytes (at most [`MAX_HEAD`]).
    Complete(Head, usize),
    /// The start of a head: more bytes may complete it.
    Partial,
    /// No head ends within [`MAX_HEAD`] bytes, or it has more headers than the server reads:
    /// 431.
    TooLarge,
    /// Not an HTTP request head: 400.
    Malformed,
}

/// The most headers a request may have.
const MAX_HEADERS: usize = 64;

/// Parses a request head from the start of `buf`, looking at its first [`MAX_HEAD`] bytes
/// only: a head of exactly [`MAX_HEAD`] bytes is complete, one byte more is too large,
/// however the bytes arrived.
pub(super) fn parse_head(buf: &[u8]) -> Parsed {
    let window = buf.get(..MAX_HEAD).unwrap_or(buf);
    let mut headers = [httparse::EMPTY_HEADER; MAX_HEADERS];
    let mut req = httparse::Request::new(&mut headers);
    let n = match req.parse(window) {
        Ok(httparse::Status::Complete(n)) => n,
        Ok(httparse::Status::Partial) if buf.len() >= MAX_HEAD => return Parsed::TooLarge,
        Ok(httparse::Status::Partial) => return Parsed::Partial,
        Err(httparse::Error::TooManyHeaders) => return Parsed::TooLarge,
        Err(_) => return Parsed::Malformed,
    };
    let http11 = req.version == Some(1);
    let headers: &[httparse::Header<'_>] = req.headers;
    let header = |name: &str| -> Vec<String> {
        headers
            .iter()
            .filter(|h| h.name.eq_ignore_ascii_case(name))
            .map(|h| String::from_utf8_lossy(h.value).trim().to_ascii_lowercase())
            .collect()
    };
    let connection = header("connection");
    let has = |word: &str| {
        connection
            .iter()
            .any(|v| v.split(',').any(|t| t.trim() == word))
    };
    let close = if http11 {
        has("close")
    } else {
        !has("keep-alive")
    };
    let body = !header("transfer-encoding").is_empty()
        || header("content-length").iter().any(|v| v != "0");
    let head = Head {
        method: req.method.unwrap_or("").to_owned(),
        path: req.path.unwrap_or("/").to_owned(),
        hosts: header("host"),
        http11,
        close,
        body,
    };
    Parsed::Complete(head, n)
}

/// True for `localhost`, `127.0.0.1` or `[::1]`, with or without a port.
pub(super) fn is_loopback_host(host: &str) -> bool {
    let (name, port) = match host.strip_prefix('[') {
        Some(rest) => match rest.split_once(']') {
            Some((inside, after)) => (format!("[{inside}]"), after),
            None => return false,
        },
        None => match host.find(':') {
            Some(i) => (host[..i].to_owned(), &host[i..]),
            None => (host.to_owned(), ""),
        },
    };
    let port_ok = match port.strip_prefix(':') {
        Some(digits) => !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()),
        None => port.is_empty(),
    };
    port_ok && matches!(name.as_str(), "localhost" | "127.0.0.1" | "[::1]")
}

/// A response ready to be written: its head, its body (borrowed from the site, or a static
/// message) and whether the connection closes after it.
pub(super) struct Response<'s> {
    pub(super) head: Vec<u8>,
    pub(super) body: &'s [u8],
    pub(super) close: bool,
}

/// A response: the status, `headers`, a `Content-Length`, `Cache-Control: no-store` and
/// `Connection`; the body unless `head_only`.
fn response<'s>(
    code: u16,
    reason: &str,
    headers: &[(&str, &str)],
    body: &'s [u8],
    head_only: bool,
    close: bool,
) -> Response<'s> {
    let mut out = format!("HTTP/1.1 {code} {reason}\r\n");
    for (name, value) in headers {
        out.push_str(&format!("{name}: {value}\r\n"));
    }
    out.push_str(&format!(
        "Content-Length: {}\r\nCache-Control: no-store\r\nX-Content-Type-Options: nosniff\r\nConnection: {}\r\n\r\n",
        body.len(),
        if close { "close" } else { "keep-alive" }
    ));
    Response {
        head: out.into_bytes(),
        body: if head_only { &[] } else { body },
        close,
    }
}

/// The answer to a request that is not read: 400 for a malformed head, 431 for one too large,
/// 503 when every place is taken by a response being written; the connection closes after it.
pub(super) fn refusal(code: u16) -> Response<'static> {
    let (reason, body): (&str, &'static [u8]) = match code {
        431 => (
            "Request Header Fields Too Large",
            b"request head too large\n",
        ),
        503 => ("Service Unavailable", b"busy\n"),
        _ => ("Bad Request", b"bad request\n"),
    };
    response(code, reason, &[], body, false, true)
}

/// Answers one request from `site`.
pub(super) fn answer<'s>(site: &'s Site, head: &Head) -> Response<'s> {
    let host_ok = match head.hosts.as_slice() {
        [host] => is_loopback_host(host),
        // HTTP/1.0 may leave `Host` out: refused like a foreign name, as the server cannot
        // tell which name the client used (a DNS-rebound page would leave it out too).
        [] if !head.http11 => false,
        _ => {
            let body = b"one Host header is needed\n";
            return response(400, "Bad Request", &[], body, false, true);
        }
    };
    let head_only = head.method == "HEAD";
    if !host_ok {
        let body = b"footprint serve answers only to localhost, 127.0.0.1 and [::1]\n";
        return response(403, "Forbidden", &[], body, head_only, true);
    }
    if !matches!(head.method.as_str(), "GET" | "HEAD") {
        let allow = [("Allow", "GET, HEAD")];
        let body = b"GET or HEAD only\n";
        return response(405, "Method Not Allowed", &allow, body, false, true);
    }
    let path = head.path.split('?').next().unwrap_or("/");
    let close = head.close || head.body;
    match site.find(path) {
        Some(asset) => {
            let kind = [("Content-Type", asset.kind)];
            response(200, "OK", &kind, &asset.bytes, head_only, close)
        }
        None => response(404, "Not Found", &[], b"not found\n", head_only, close),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn loopback_hosts_only() {
        for ok in [
            "localhost",
            "localhost:8080",
            "127.0.0.1",
            "127.0.0.1:1",
            "[::1]",
            "[::1]:80",
        ] {
            assert!(is_loopback_host(ok), "{ok}");
        }
        for bad in [
            "",
            "evil.example",
            "localhost.evil.example",
            "127.0.0.1.evil.example",
            "localhost:",
            "localhost:80x",
            "[::1",
            "[::2]:80",
            "127.0.0.2",
        ] {
            assert!(!is_loopback_host(bad), "{bad}");
        }
    }

    fn complete(buf: &[u8]) -> (Head, usize) {
        match parse_head(buf) {
            Parsed::Complete(h, n) => (h, n),
            _ => panic!("not a complete head: {:?}", String::from_utf8_lossy(buf)),
        }
    }

    #[test]
    fn heads_parse_and_say_when_to_close() {
        let (h, n) = complete(b"GET /a?b HTTP/1.1\r\nHost: x\r\n\r\nrest");
        assert_eq!((h.method.as_str(), h.path.as_str(), n), ("GET", "/a?b", 30));
        assert!(h.http11 && !h.close && !h.body);
        assert_eq!(h.hosts, ["x"]);
        let (h, _) = complete(b"GET / HTTP/1.0\r\n\r\n");
        assert!(h.close && h.hosts.is_empty());
        let (h, _) = complete(b"POST / HTTP/1.1\r\nContent-Length: 3\r\n\r\n");
        assert!(h.body);
        assert!(matches!(
            parse_head(b"GET / HTTP/1.1\r\nHost"),
            Parsed::Partial
        ));
        assert!(matches!(parse_head(b"NONSENSE\r\n\r\n"), Parsed::Malformed));
    }

    /// A request head of `len` bytes.
    fn head_of(len: usize) -> Vec<u8> {
        let start = b"GET / HTTP/1.1\r\nHost: localhost\r\nX-Pad: ".as_slice();
        let mut head = start.to_vec();
        head.resize(len - 4, b'p');
        head.extend_from_slice(b"\r\n\r\n");
        head
    }

    #[test]
    fn the_head_limit_is_exact() {
        let (_, n) = complete(&head_of(MAX_HEAD));
        assert_eq!(n, MAX_HEAD);
        // With the next request behind it (pipelined), still.
        let mut two = head_of(MAX_HEAD);
        two.extend_from_slice(&head_of(100));
        assert_eq!(complete(&two).1, MAX_HEAD);
        let over = head_of(MAX_HEAD + 1);
        assert!(matches!(parse_head(&over), Parsed::TooLarge));
        // Its first MAX_HEAD bytes alone: too large already, however the rest comes.
        assert!(matches!(parse_head(&over[..MAX_HEAD]), Parsed::TooLarge));
        assert!(matches!(parse_head(&over[..MAX_HEAD - 1]), Parsed::Partial));
        let mut many = b"GET / HTTP/1.1\r\n".to_vec();
        for i in 0..=MAX_HEADERS {
            many.extend_from_slice(format!("X-{i}: 1\r\n").as_bytes());
        }
        many.extend_from_slice(b"\r\n");
        assert!(matches!(parse_head(&many), Parsed::TooLarge));
    }
}
