//! `footprint serve`: the browser page (`web/`), from 127.0.0.1 only.
//!
//! The page, its script and the WebAssembly core are built into the binary (the `.wasm` by
//! `host/build.rs`); a `--dem` map (and its `--color`) is read once, when the server starts,
//! checked there with the CLI's readers, and served from memory as the bytes the user gave,
//! for the page to read with the same readers compiled to WebAssembly.
//!
//! The server holds under hostile or broken clients: each connection has a thread of its own
//! (at most [`MAX_CONNECTIONS`] at once; one more is answered 503 and closed), a request's
//! head must arrive within [`READ_TIMEOUT`] and be at most [`MAX_HEAD`] bytes, and a client
//! that stops reading is dropped after [`WRITE_TIMEOUT`], so a client that never reads blocks
//! no one but itself. Only GET and HEAD are answered (405 otherwise), and only to requests
//! whose `Host` is a loopback name (`localhost`, `127.0.0.1`, `[::1]`, with any port; 403
//! otherwise), so a page on another site that rebinds its DNS name to 127.0.0.1 cannot read
//! the user's map. Requests are parsed by `httparse`.

use std::io::{Read, Write};
use std::net::{Ipv4Addr, SocketAddr, TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use anyhow::{bail, Context, Result};
use clap::Args;

use crate::map::{self, LoadOptions};

/// The page's WebAssembly core, built by `host/build.rs` (empty if it could not be built).
const WASM: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/footprint_web.wasm"));
// Copied from web/static by host/build.rs, so that the packaged crate builds too.
const INDEX: &str = include_str!(concat!(env!("OUT_DIR"), "/index.html"));
const SCRIPT: &str = include_str!(concat!(env!("OUT_DIR"), "/app.js"));
const STYLE: &str = include_str!(concat!(env!("OUT_DIR"), "/style.css"));

/// Connections served at once; one more is answered 503 and closed.
pub const MAX_CONNECTIONS: usize = 256;
/// How long a request's head may take to arrive, all of it (and a kept-alive connection may
/// stay idle).
pub const READ_TIMEOUT: Duration = Duration::from_secs(10);
/// How long a write may wait for a client that does not read before the connection is dropped.
pub const WRITE_TIMEOUT: Duration = Duration::from_secs(10);
/// The largest request head (request line and headers), bytes.
pub const MAX_HEAD: usize = 16 * 1024;

/// `footprint serve`.
#[derive(Args, Debug)]
pub struct ServeArgs {
    /// The port on 127.0.0.1 (0: any free port; the address is printed).
    #[arg(long, default_value_t = 8080)]
    pub port: u16,
    /// A height map for the page to open instead of the built-in terrain (.png, .asc, .hgt,
    /// .tif), read once when the server starts and in the browser by the CLI's readers.
    #[arg(long, value_name = "FILE")]
    pub dem: Option<PathBuf>,
    /// Its colour map (a PNG of the same size).
    #[arg(long, value_name = "COLOR.png", requires = "dem")]
    pub color: Option<PathBuf>,
    /// Seed of the built-in terrain (the page takes seeds up to 2^32 − 1).
    #[arg(long, default_value_t = 1, conflicts_with = "dem")]
    pub seed: u32,
    /// Side of the built-in terrain, voxels.
    #[arg(long = "terrain-size", default_value_t = map::DEFAULT_SIZE, conflicts_with = "dem")]
    pub terrain_size: u32,
}

/// A file the page may fetch: its bytes and content type.
struct Asset {
    bytes: Vec<u8>,
    kind: &'static str,
}

/// Everything the server answers with, by URL path.
struct Site {
    assets: Vec<(String, Asset)>,
}

impl Site {
    fn find(&self, path: &str) -> Option<&Asset> {
        self.assets.iter().find(|(p, _)| p == path).map(|(_, a)| a)
    }
}

/// Serves the page until interrupted.
pub fn serve(args: &ServeArgs) -> Result<()> {
    let map = map_files(args)?;
    if WASM.is_empty() {
        // One line with the one command that fixes it (host/build.rs says why it was left out).
        if env!("FOOTPRINT_WASM_MISSING").contains("FOOTPRINT_NO_WASM") {
            bail!(
                "serve: this binary was built with FOOTPRINT_NO_WASM set, without the page; \
                 build it without: `cargo run --release -- serve`"
            );
        }
        bail!(
            "serve: the page needs the WebAssembly target, once: `rustup target add \
             wasm32-unknown-unknown`, then `cargo run --release -- serve` again"
        );
    }
    let mut assets = vec![
        ("/".to_owned(), text(INDEX, "text/html; charset=utf-8")),
        (
            "/index.html".to_owned(),
            text(INDEX, "text/html; charset=utf-8"),
        ),
        (
            "/app.js".to_owned(),
            text(SCRIPT, "text/javascript; charset=utf-8"),
        ),
        (
            "/style.css".to_owned(),
            text(STYLE, "text/css; charset=utf-8"),
        ),
        (
            "/footprint_web.wasm".to_owned(),
            Asset {
                bytes: WASM.to_vec(),
                kind: "application/wasm",
            },
        ),
        ("/map.json".to_owned(), text(&map.json, "application/json")),
    ];
    for (url, bytes) in map.files {
        assets.push((
            url,
            Asset {
                bytes,
                kind: "application/octet-stream",
            },
        ));
    }
    let site = Arc::new(Site { assets });
    let addr = SocketAddr::from((Ipv4Addr::LOCALHOST, args.port));
    let listener = TcpListener::bind(addr).map_err(|e| match e.kind() {
        std::io::ErrorKind::AddrInUse => {
            anyhow::anyhow!("--port {}: already in use on 127.0.0.1", args.port)
        }
        _ => anyhow::anyhow!("--port {}: cannot listen on 127.0.0.1 ({e})", args.port),
    })?;
    let port = listener.local_addr()?.port();
    crate::outln!("serving the page at http://127.0.0.1:{port}/ (Ctrl-C stops)")?;
    crate::console::flush()?;
    let live = Arc::new(AtomicUsize::new(0));
    for stream in listener.incoming() {
        let stream = match stream {
            Ok(s) => s,
            // Out of descriptors, or a connection reset before it was accepted: go on.
            Err(_) => {
                std::thread::sleep(Duration::from_millis(10));
                continue;
            }
        };
        if live.load(Ordering::Acquire) >= MAX_CONNECTIONS {
            let _ = stream.set_write_timeout(Some(Duration::from_secs(1)));
            let _ = respond(
                &stream,
                503,
                "Service Unavailable",
                &[],
                b"busy\n",
                false,
                false,
            );
            continue;
        }
        let slot = Slot::take(&live);
        let site = Arc::clone(&site);
        // If the thread cannot start, the closure (and its slot) is dropped with the stream.
        let _ = std::thread::Builder::new()
            .name("serve-connection".to_owned())
            .spawn(move || {
                let _slot = slot;
                let _ = connection(stream, &site);
            });
    }
    Ok(())
}

/// One connection's place among the [`MAX_CONNECTIONS`], given back when dropped.
struct Slot(Arc<AtomicUsize>);

impl Slot {
    fn take(live: &Arc<AtomicUsize>) -> Self {
        live.fetch_add(1, Ordering::AcqRel);
        Slot(Arc::clone(live))
    }
}

impl Drop for Slot {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::AcqRel);
    }
}

/// A request's head, as far as the server reads it.
struct Head {
    method: String,
    path: String,
    /// The `Host` headers' values.
    hosts: Vec<String>,
    /// HTTP/1.1 (else 1.0).
    http11: bool,
    /// `Connection: close` (1.1) or no `Connection: keep-alive` (1.0).
    close: bool,
    /// A body follows (`Content-Length` > 0 or `Transfer-Encoding`): the server reads none,
    /// so it closes the connection after answering.
    body: bool,
}

/// Parses a request head from the start of `buf`: `Ok(Some((head, its length)))`, `Ok(None)`
/// if more bytes are needed, `Err` if it is malformed.
fn parse_head(buf: &[u8]) -> Result<Option<(Head, usize)>, httparse::Error> {
    let mut headers = [httparse::EMPTY_HEADER; 64];
    let mut req = httparse::Request::new(&mut headers);
    let n = match req.parse(buf)? {
        httparse::Status::Complete(n) => n,
        httparse::Status::Partial => return Ok(None),
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
    Ok(Some((head, n)))
}

/// True for `localhost`, `127.0.0.1` or `[::1]`, with or without a port.
fn is_loopback_host(host: &str) -> bool {
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

/// Serves the requests of one connection until it closes, fails or times out.
fn connection(stream: TcpStream, site: &Site) -> std::io::Result<()> {
    stream.set_write_timeout(Some(WRITE_TIMEOUT))?;
    stream.set_nodelay(true)?;
    let mut buf: Vec<u8> = Vec::with_capacity(4096);
    let mut chunk = [0u8; 4096];
    loop {
        // The whole head within READ_TIMEOUT, however it trickles in.
        let deadline = Instant::now() + READ_TIMEOUT;
        let (head, len) = loop {
            match parse_head(&buf) {
                Ok(Some(parsed)) => break parsed,
                Ok(None) if buf.len() < MAX_HEAD => {}
                Ok(None) => {
                    let body = b"request head too large\n";
                    return respond(
                        &stream,
                        431,
                        "Request Header Fields Too Large",
                        &[],
                        body,
                        false,
                        true,
                    );
                }
                Err(_) => {
                    return respond(
                        &stream,
                        400,
                        "Bad Request",
                        &[],
                        b"bad request\n",
                        false,
                        true,
                    );
                }
            }
            let left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() {
                return Ok(());
            }
            stream.set_read_timeout(Some(left))?;
            let n = (&stream).read(&mut chunk)?;
            if n == 0 {
                return Ok(());
            }
            buf.extend_from_slice(chunk.get(..n).unwrap_or_default());
        };
        buf.drain(..len);
        if !answer(&stream, site, &head)? || head.close || head.body {
            return Ok(());
        }
    }
}

/// Answers one request; false if the connection must close after it.
fn answer(stream: &TcpStream, site: &Site, head: &Head) -> std::io::Result<bool> {
    let host_ok = match head.hosts.as_slice() {
        [host] => is_loopback_host(host),
        [] if !head.http11 => true,
        _ => {
            respond(
                stream,
                400,
                "Bad Request",
                &[],
                b"one Host header is needed\n",
                false,
                true,
            )?;
            return Ok(false);
        }
    };
    if !host_ok {
        let body = b"footprint serve answers only to localhost, 127.0.0.1 and [::1]\n";
        respond(stream, 403, "Forbidden", &[], body, false, true)?;
        return Ok(false);
    }
    let head_only = match head.method.as_str() {
        "GET" => false,
        "HEAD" => true,
        _ => {
            let allow = [("Allow", "GET, HEAD")];
            respond(
                stream,
                405,
                "Method Not Allowed",
                &allow,
                b"GET or HEAD only\n",
                false,
                true,
            )?;
            return Ok(false);
        }
    };
    let path = head.path.split('?').next().unwrap_or("/");
    let keep = !(head.close || head.body);
    match site.find(path) {
        Some(asset) => {
            let kind = [("Content-Type", asset.kind)];
            respond(stream, 200, "OK", &kind, &asset.bytes, head_only, !keep)?;
        }
        None => respond(
            stream,
            404,
            "Not Found",
            &[],
            b"not found\n",
            head_only,
            !keep,
        )?,
    }
    Ok(keep)
}

/// Writes a response: the status, `headers`, a `Content-Length`, `Cache-Control: no-store`
/// and `Connection`; the body unless `head_only`.
fn respond(
    mut stream: &TcpStream,
    code: u16,
    reason: &str,
    headers: &[(&str, &str)],
    body: &[u8],
    head_only: bool,
    close: bool,
) -> std::io::Result<()> {
    let mut out = format!("HTTP/1.1 {code} {reason}\r\n");
    for (name, value) in headers {
        out.push_str(&format!("{name}: {value}\r\n"));
    }
    out.push_str(&format!(
        "Content-Length: {}\r\nCache-Control: no-store\r\nX-Content-Type-Options: nosniff\r\nConnection: {}\r\n\r\n",
        body.len(),
        if close { "close" } else { "keep-alive" }
    ));
    stream.write_all(out.as_bytes())?;
    if !head_only {
        stream.write_all(body)?;
    }
    stream.flush()
}

/// The page's map: `map.json` (the built-in terrain's seed and side, or the URLs and names of
/// the files) and the files' bytes by URL, read once.
struct MapFiles {
    json: String,
    files: Vec<(String, Vec<u8>)>,
}

/// Reads `--dem` (and `--color`) once, checks them with the CLI's readers, and lists them for
/// the page.
fn map_files(args: &ServeArgs) -> Result<MapFiles> {
    let Some(dem) = &args.dem else {
        map::procedural::check_size(args.terrain_size).map_err(anyhow::Error::msg)?;
        let json = serde_json::json!({ "seed": args.seed, "terrain_size": args.terrain_size });
        return Ok(MapFiles {
            json: json.to_string(),
            files: Vec::new(),
        });
    };
    let read = |option: &str, path: &Path| -> Result<Vec<u8>> {
        let what = format!("{option} {}", crate::output::shown(path));
        Ok(footprint_maps::input::read_all(path, &what)?)
    };
    let dem_bytes = read("--dem", dem)?;
    let color_bytes = args
        .color
        .as_deref()
        .map(|c| read("--color", c))
        .transpose()?;
    let mut in_memory: Vec<(&Path, &[u8])> = vec![(dem.as_path(), dem_bytes.as_slice())];
    if let (Some(c), Some(b)) = (&args.color, &color_bytes) {
        in_memory.push((c.as_path(), b.as_slice()));
    }
    map::load(
        dem,
        &LoadOptions {
            color: args.color.as_deref(),
            in_memory: &in_memory,
            ..LoadOptions::default()
        },
    )
    .with_context(|| format!("--dem {}", crate::output::shown(dem)))?;
    let name = |p: &Path| -> Result<String> {
        p.file_name()
            .and_then(|n| n.to_str())
            .map(str::to_owned)
            .with_context(|| format!("--dem {:?}: the page needs a file name in UTF-8", p))
    };
    let mut json = serde_json::json!({ "height": { "url": "/map/height", "name": name(dem)? } });
    let mut files = vec![("/map/height".to_owned(), dem_bytes)];
    if let (Some(color), Some(bytes)) = (&args.color, color_bytes) {
        json["color"] = serde_json::json!({ "url": "/map/color", "name": name(color)? });
        files.push(("/map/color".to_owned(), bytes));
    }
    Ok(MapFiles {
        json: json.to_string(),
        files,
    })
}

fn text(s: &str, kind: &'static str) -> Asset {
    Asset {
        bytes: s.as_bytes().to_vec(),
        kind,
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

    #[test]
    fn heads_parse_and_say_when_to_close() {
        let (h, n) = parse_head(b"GET /a?b HTTP/1.1\r\nHost: x\r\n\r\nrest")
            .unwrap()
            .unwrap();
        assert_eq!((h.method.as_str(), h.path.as_str(), n), ("GET", "/a?b", 30));
        assert!(h.http11 && !h.close && !h.body);
        assert_eq!(h.hosts, ["x"]);
        let (h, _) = parse_head(b"GET / HTTP/1.0\r\n\r\n").unwrap().unwrap();
        assert!(h.close && h.hosts.is_empty());
        let (h, _) = parse_head(b"POST / HTTP/1.1\r\nContent-Length: 3\r\n\r\n")
            .unwrap()
            .unwrap();
        assert!(h.body);
        assert!(parse_head(b"GET / HTTP/1.1\r\nHost").unwrap().is_none());
        assert!(parse_head(b"NONSENSE\r\n\r\n").is_err());
    }
}
