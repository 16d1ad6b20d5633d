//! A `footprint serve` and a headless Chromium driven over the DevTools protocol, for the
//! browser test (`tests/browser.rs`) and the browser benchmark (`benches/browser.rs`).

#![allow(dead_code)] // each user takes a part

use std::io::{BufRead, BufReader, Read, Write};
use std::net::{Ipv4Addr, TcpStream};
use std::os::unix::process::CommandExt as _;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use base64::Engine as _;
use serde_json::{json, Value};

/// Starts `footprint serve --port 0 ARGS…` and reads the first line it prints on stdout (the
/// address it serves, or nothing if it refused: its stderr says why).
pub fn spawn_serve(args: &[&str]) -> (Child, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_footprint"))
        .args(["serve", "--port", "0"])
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("footprint serve starts");
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    (child, line)
}

/// A running `footprint serve --port 0 ARGS…`, killed when dropped.
pub struct Served {
    child: Child,
    /// The port it listens on.
    pub port: u16,
}

impl Served {
    /// Starts it.
    pub fn start(args: &[&str]) -> Self {
        let (mut child, line) = spawn_serve(args);
        let port = line
            .split("127.0.0.1:")
            .nth(1)
            .and_then(|s| s.split('/').next())
            .and_then(|p| p.parse().ok())
            .unwrap_or_else(|| {
                let mut err = String::new();
                child.stderr.take().unwrap().read_to_string(&mut err).ok();
                panic!("serve printed {line:?}, stderr {err:?}")
            });
        Self { child, port }
    }
}

impl Drop for Served {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A headless Chromium on one page, and a DevTools connection to it; killed when dropped.
pub struct Browser {
    child: Child,
    _profile: tempfile::TempDir,
    socket: tungstenite::WebSocket<tungstenite::stream::MaybeTlsStream<TcpStream>>,
    next_id: u64,
}

/// Debian's Chromium, if it is installed.
pub fn chromium() -> Option<PathBuf> {
    std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths)
            .map(|d| d.join("chromium"))
            .find(|p| p.is_file())
    })
}

/// A plain HTTP/1.1 GET on loopback: the body, by its `Content-Length` (Chromium's DevTools
/// endpoint answers HTTP/1.1 only, and keeps the connection open).
pub fn http_get(port: u16, path: &str) -> Vec<u8> {
    let s = TcpStream::connect((Ipv4Addr::LOCALHOST, port)).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(30))).unwrap();
    let mut w = &s;
    write!(
        w,
        "GET {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nAccept: */*\r\n\r\n"
    )
    .unwrap();
    let mut r = BufReader::new(&s);
    let mut len = 0;
    loop {
        let mut line = String::new();
        r.read_line(&mut line).unwrap();
        let line = line.trim_end();
        if line.is_empty() {
            break;
        }
        if let Some((name, value)) = line.split_once(':') {
            if name.eq_ignore_ascii_case("content-length") {
                len = value.trim().parse().unwrap();
            }
        }
    }
    let mut body = vec![0; len];
    r.read_exact(&mut body).unwrap();
    body
}

impl Browser {
    /// Opens `url` in a fresh headless Chromium (the flags the machine's notes give: no
    /// sandbox as root, no GPU, no background networking).
    pub fn open(exe: &Path, url: &str) -> Self {
        let profile = tempfile::tempdir().unwrap();
        let child = Command::new(exe)
            .args([
                "--headless",
                "--no-sandbox",
                "--disable-gpu",
                "--disable-quic",
                "--no-first-run",
                "--disable-background-networking",
                "--disable-component-update",
                "--disable-sync",
                "--remote-debugging-port=0",
                "--window-size=1000,900",
            ])
            .arg(format!("--user-data-dir={}", profile.path().display()))
            .arg(url)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            // Its own process group, so that every process it starts is killed with it.
            .process_group(0)
            .spawn()
            .expect("chromium starts");
        // Chromium writes its DevTools port to the profile once it listens.
        let port_file = profile.path().join("DevToolsActivePort");
        let start = Instant::now();
        let port: u16 = loop {
            if let Some(p) = std::fs::read_to_string(&port_file)
                .ok()
                .and_then(|t| t.lines().next().and_then(|l| l.parse().ok()))
            {
                break p;
            }
            assert!(
                start.elapsed() < Duration::from_secs(60),
                "chromium gave no DevTools port"
            );
            std::thread::sleep(Duration::from_millis(100));
        };
        let ws = loop {
            let list: Value =
                serde_json::from_slice(&http_get(port, "/json/list")).unwrap_or(json!([]));
            let page = list.as_array().and_then(|l| {
                l.iter()
                    .find(|t| {
                        t["type"] == "page"
                            && t["url"].as_str().is_some_and(|u| u.starts_with("http"))
                    })
                    .and_then(|t| t["webSocketDebuggerUrl"].as_str().map(str::to_owned))
            });
            if let Some(ws) = page {
                break ws;
            }
            assert!(
                start.elapsed() < Duration::from_secs(60),
                "chromium opened no page"
            );
            std::thread::sleep(Duration::from_millis(100));
        };
        let (socket, _) = tungstenite::connect(ws.as_str()).expect("the DevTools socket");
        Self {
            child,
            _profile: profile,
            socket,
            next_id: 1,
        }
    }

    /// Calls DevTools method `method` and returns its result.
    pub fn call(&mut self, method: &str, params: Value) -> Value {
        let id = self.next_id;
        self.next_id += 1;
        let msg = json!({ "id": id, "method": method, "params": params }).to_string();
        self.socket
            .send(tungstenite::Message::Text(msg.into()))
            .unwrap();
        loop {
            let reply = self.socket.read().expect("a DevTools reply");
            let Ok(text) = reply.to_text() else { continue };
            let v: Value = serde_json::from_str(text).unwrap_or(Value::Null);
            if v["id"] == id {
                assert!(v.get("error").is_none(), "{method}: {v}");
                return v["result"].clone();
            }
        }
    }

    /// Evaluates `expression` in the page (awaiting a promise) and returns its value.
    pub fn eval(&mut self, expression: &str) -> Value {
        let r = self.call(
            "Runtime.evaluate",
            json!({ "expression": expression, "awaitPromise": true, "returnByValue": true }),
        );
        assert!(r.get("exceptionDetails").is_none(), "{expression}: {r}");
        r["result"]["value"].clone()
    }

    /// Waits until `condition` (a JavaScript expression) is true, up to `secs` seconds.
    pub fn wait_for(&mut self, condition: &str, secs: u64) {
        let start = Instant::now();
        // Before the page has parsed, `document.body` is null: that is "not yet", not an error.
        let guarded = format!("(() => {{ try {{ return ({condition}) === true; }} catch (e) {{ return false; }} }})()");
        while self.eval(&guarded) != json!(true) {
            let message = self.eval("document.getElementById('message')?.textContent ?? ''");
            assert!(
                start.elapsed() < Duration::from_secs(secs),
                "waited {secs} s for {condition}; the page says {message}"
            );
            std::thread::sleep(Duration::from_millis(200));
        }
    }

    /// A PNG of the page.
    pub fn screenshot(&mut self) -> Vec<u8> {
        let r = self.call("Page.captureScreenshot", json!({ "format": "png" }));
        base64::engine::general_purpose::STANDARD
            .decode(r["data"].as_str().unwrap())
            .unwrap()
    }
}

impl Drop for Browser {
    /// Kills Chromium's whole process group (its zygote and renderers too).
    fn drop(&mut self) {
        let group = format!("-{}", self.child.id());
        let _ = Command::new("kill").args(["-KILL", "--", &group]).status();
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Whether this `footprint` has the browser page built in; if not (no `rustup target add
/// wasm32-unknown-unknown` on this machine, or `FOOTPRINT_NO_WASM`), prints a warning, as
/// for a missing Chromium, and the caller skips its test: `cargo test --workspace` passes on a
/// machine without the wasm32 target. CI installs the target, so there the tests run.
pub fn page_or_warn() -> bool {
    let (mut child, line) = spawn_serve(&["--terrain-size", "16"]);
    if line.starts_with("serving the page") {
        let _ = child.kill();
        let _ = child.wait();
        return true;
    }
    let mut err = String::new();
    child.stderr.take().unwrap().read_to_string(&mut err).ok();
    let _ = child.wait();
    let missing = err.contains("wasm32-unknown-unknown") || err.contains("FOOTPRINT_NO_WASM");
    assert!(missing, "serve failed: {err}");
    eprintln!(
        "WARNING: footprint was built without the browser page (rustup target add \
         wasm32-unknown-unknown): the test is skipped"
    );
    false
}
