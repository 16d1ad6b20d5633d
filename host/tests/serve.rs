//! `footprint serve` under hostile clients (issue 28, class 9): a client that never reads
//! blocks no one, methods other than GET and HEAD get 405, a foreign `Host` (DNS rebinding)
//! gets 403, and the `--dem` map is read once, when the server starts. Loopback only.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::{Ipv4Addr, TcpStream};
use std::time::{Duration, Instant};

mod common;

use common::browser::Served;

/// A raw exchange: writes `request`, reads until the server closes or `Content-Length` bytes
/// of body came; gives the status code, the header lines and the body.
fn exchange(port: u16, request: &str) -> (u16, Vec<String>, Vec<u8>) {
    let s = TcpStream::connect((Ipv4Addr::LOCALHOST, port)).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
    (&s).write_all(request.as_bytes()).unwrap();
    let mut r = BufReader::new(&s);
    let mut status_line = String::new();
    r.read_line(&mut status_line).unwrap();
    let status = status_line
        .split_whitespace()
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap_or_else(|| panic!("no status line: {status_line:?}"));
    let mut headers = Vec::new();
    let mut len = None;
    loop {
        let mut line = String::new();
        r.read_line(&mut line).unwrap();
        let line = line.trim_end().to_owned();
        if line.is_empty() {
            break;
        }
        if let Some((name, value)) = line.split_once(':') {
            if name.eq_ignore_ascii_case("content-length") {
                len = value.trim().parse::<usize>().ok();
            }
        }
        headers.push(line);
    }
    let mut body = Vec::new();
    if request.starts_with("HEAD ") {
        return (status, headers, body);
    }
    match len {
        Some(n) => {
            body.resize(n, 0);
            r.read_exact(&mut body).unwrap();
        }
        None => {
            r.read_to_end(&mut body).unwrap();
        }
    }
    (status, headers, body)
}

fn get(port: u16, path: &str, host: &str) -> (u16, Vec<String>, Vec<u8>) {
    exchange(
        port,
        &format!("GET {path} HTTP/1.1\r\nHost: {host}\r\nConnection: close\r\n\r\n"),
    )
}

/// The load test: one client asks for the page's WebAssembly 400 times without reading a
/// byte, so the server's writes to it block; 199 others, all at once, must each still get the
/// page within 5 s (a liveness bound: each answer takes milliseconds). Before: one thread
/// wrote every response, so all 199 waited for ever behind the stalled one.
#[test]
fn a_client_that_never_reads_blocks_no_one() {
    let served = Served::start(&[]);
    let port = served.port;
    let stalled = TcpStream::connect((Ipv4Addr::LOCALHOST, port)).unwrap();
    let ask = format!("GET /footprint_web.wasm HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n");
    let mut w = &stalled;
    for _ in 0..400 {
        if w.write_all(ask.as_bytes()).is_err() {
            break;
        }
    }
    // Let the server fill the stalled client's socket and block on it.
    std::thread::sleep(Duration::from_millis(500));
    let started = Instant::now();
    let clients: Vec<_> = (0..199)
        .map(|_| {
            std::thread::spawn(move || {
                let (status, _, body) = get(port, "/", &format!("127.0.0.1:{port}"));
                (status, body.len(), started.elapsed())
            })
        })
        .collect();
    for c in clients {
        let (status, len, took) = c.join().expect("a client got no answer in 10 s");
        assert_eq!(status, 200);
        assert!(len > 0);
        assert!(
            took < Duration::from_secs(5),
            "an answer took {took:?} (bound: 5 s)"
        );
    }
    drop(stalled);
    // Still serving.
    assert_eq!(get(port, "/", "localhost").0, 200);
}

/// The server's rules: GET and HEAD only (405 with `Allow` otherwise), loopback `Host` names
/// only (403 otherwise: a DNS-rebound page cannot read the user's map), a bad request gets
/// 400, and the `--dem` file is read once at start (changing it later changes nothing).
/// Before: every method got 200, any Host was served, and the map was re-read by path on each
/// request, an unreadable one served as an empty 200.
#[test]
fn only_get_and_head_from_loopback_names_and_the_map_read_once() {
    let dir = tempfile::tempdir().unwrap();
    let grid = dir.path().join("g.asc");
    let text = "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 10\n1 2 3\n4 5 6\n";
    std::fs::write(&grid, text).unwrap();
    let served = Served::start(&["--dem", grid.to_str().unwrap()]);
    let port = served.port;
    std::fs::write(&grid, "changed").unwrap();
    let (status, _, body) = get(port, "/map/height", &format!("127.0.0.1:{port}"));
    assert_eq!((status, body.as_slice()), (200, text.as_bytes()));
    std::fs::remove_file(&grid).unwrap();
    let (status, _, body) = get(port, "/map/height", "localhost");
    assert_eq!((status, body.as_slice()), (200, text.as_bytes()));
    for method in ["POST", "PUT", "DELETE", "OPTIONS", "PATCH"] {
        let (status, headers, _) = exchange(
            port,
            &format!(
                "{method} / HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 0\r\nConnection: close\r\n\r\n"
            ),
        );
        assert_eq!(status, 405, "{method}");
        assert!(
            headers
                .iter()
                .any(|h| h.to_ascii_lowercase().starts_with("allow: get, head")),
            "{method}: {headers:?}"
        );
    }
    let (status, headers, body) = exchange(
        port,
        &format!("HEAD / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nConnection: close\r\n\r\n"),
    );
    assert_eq!(status, 200);
    assert!(body.is_empty());
    let page_len = get(port, "/", "localhost").2.len();
    assert!(
        headers
            .iter()
            .any(|h| h.eq_ignore_ascii_case(&format!("content-length: {page_len}"))),
        "{headers:?}"
    );
    for host in [
        "localhost",
        "127.0.0.1",
        "[::1]",
        &format!("localhost:{port}"),
    ] {
        assert_eq!(get(port, "/", host).0, 200, "Host: {host}");
    }
    for host in [
        "evil.example",
        &format!("evil.example:{port}"),
        "127.0.0.1.evil.example",
        "localhost.evil.example",
        "",
    ] {
        let (status, _, body) = get(port, "/map/height", host);
        assert_eq!(status, 403, "Host: {host:?}");
        assert!(!body.starts_with(b"ncols"), "Host: {host:?} got the map");
    }
    // No Host at all (an HTTP/1.1 request must have one).
    let (status, _, _) = exchange(port, "GET / HTTP/1.1\r\nConnection: close\r\n\r\n");
    assert_eq!(status, 400);
    let (status, _, _) = exchange(port, "NONSENSE\r\n\r\n");
    assert_eq!(status, 400);
}

/// A baked map (`footprint map bake`) is served as it is, for the page to read with the same
/// code (`baked::from_bytes`); a corrupt one is refused at start, in one line.
#[test]
fn a_baked_map_is_served_and_a_corrupt_one_refused() {
    let dir = tempfile::tempdir().unwrap();
    let fpmap = dir.path().join("m.fpmap");
    let fp = fpmap.to_str().unwrap();
    let o = common::footprint(&["map", "bake", "--terrain-size", "64", "--out", fp]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let bytes = std::fs::read(&fpmap).unwrap();
    let served = Served::start(&["--dem", fp]);
    let port = served.port;
    let (status, _, body) = get(port, "/map/height", "localhost");
    assert!(status == 200 && body == bytes, "status {status}");
    let (_, _, json) = get(port, "/map.json", "localhost");
    assert!(String::from_utf8_lossy(&json).contains("m.fpmap"));
    drop(served);
    let mut corrupt = bytes.clone();
    corrupt[HEADER + 10] ^= 1;
    std::fs::write(&fpmap, corrupt).unwrap();
    let args = ["serve", "--port", "0", "--dem", fp];
    let o = common::footprint_bounded(&args, 20).expect("serve refuses at once");
    common::assert_one_line_error(&o, &args, "checksum");
}

/// The first byte of a baked map's level 0.
const HEADER: usize = 4096;

/// docs/browser.md's size of the page's WebAssembly module is the one `serve` sends (issue
/// 55, item 3: it said 847,135 bytes when 1,707,494 were sent), within 10 %, which a compiler
/// release may move.
#[test]
fn the_module_size_in_browser_md_is_the_one_served() {
    if !common::browser::page_or_warn() {
        return;
    }
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/browser.md"))
        .unwrap();
    let text = doc.split_whitespace().collect::<Vec<_>>().join(" ");
    let said = text
        .split("module that `serve` sends is ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .expect("docs/browser.md says how large the module `serve` sends is");
    let said: f64 = said.replace(',', "").parse().unwrap();
    let served = Served::start(&[]);
    let (status, _, body) = get(served.port, "/footprint_web.wasm", "localhost");
    assert_eq!(status, 200);
    let sent = body.len() as f64;
    assert!(
        (said / sent - 1.0).abs() <= 0.10,
        "docs/browser.md says the module is {said} bytes; serve sent {sent}"
    );
}
