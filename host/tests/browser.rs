//! `footprint serve` and the page in a real headless browser (Debian's `chromium`, driven over
//! the DevTools protocol): the frames the WebAssembly core draws in the browser hash to the
//! same FNV-1a-64 as `footprint render`'s, a bad map file shows the CLI's one-line error and
//! keeps the map, and the server refuses a port in use and listens on loopback only.
//!
//! Without `chromium` on the PATH the browser tests print a warning and pass (`.ci/run`
//! installs it). The page's screenshot is saved as `target/browser/footprint-page.png`.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::{Ipv4Addr, TcpListener, TcpStream, UdpSocket};
use std::os::unix::process::CommandExt as _;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use base64::Engine as _;
use serde_json::{json, Value};

mod common;

use common::{assert_one_line_error, footprint};

/// A running `footprint serve --port 0 ARGS…`, killed when dropped.
struct Served {
    child: Child,
    port: u16,
}

impl Served {
    fn start(args: &[&str]) -> Self {
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
struct Browser {
    child: Child,
    _profile: tempfile::TempDir,
    socket: tungstenite::WebSocket<tungstenite::stream::MaybeTlsStream<TcpStream>>,
    next_id: u64,
}

/// Debian's Chromium, if it is installed.
fn chromium() -> Option<PathBuf> {
    std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths)
            .map(|d| d.join("chromium"))
            .find(|p| p.is_file())
    })
}

/// A plain HTTP/1.1 GET on loopback: the body, by its `Content-Length` (Chromium's DevTools
/// endpoint answers HTTP/1.1 only, and keeps the connection open).
fn http_get(port: u16, path: &str) -> Vec<u8> {
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
    fn open(exe: &Path, url: &str) -> Self {
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
    fn call(&mut self, method: &str, params: Value) -> Value {
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
    fn eval(&mut self, expression: &str) -> Value {
        let r = self.call(
            "Runtime.evaluate",
            json!({ "expression": expression, "awaitPromise": true, "returnByValue": true }),
        );
        assert!(r.get("exceptionDetails").is_none(), "{expression}: {r}");
        r["result"]["value"].clone()
    }

    /// Waits until `condition` (a JavaScript expression) is true, up to `secs` seconds.
    fn wait_for(&mut self, condition: &str, secs: u64) {
        let start = Instant::now();
        while self.eval(condition) != json!(true) {
            let message = self.eval("document.getElementById('message')?.textContent ?? ''");
            assert!(
                start.elapsed() < Duration::from_secs(secs),
                "waited {secs} s for {condition}; the page says {message}"
            );
            std::thread::sleep(Duration::from_millis(200));
        }
    }

    /// A PNG of the page.
    fn screenshot(&mut self) -> Vec<u8> {
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

/// FNV-1a-64 of a PNG's RGB bytes, row-major from the top.
fn png_hash(path: &Path) -> String {
    let img = image::open(path).unwrap().to_rgb8();
    let h = img.as_raw().iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    });
    format!("{h:016x}")
}

/// `footprint render`'s hash for the same view and mode.
fn render_hash(pitch: &str, mode: &str, size: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("frame.png");
    let o = footprint(&[
        "render",
        "--pitch",
        pitch,
        "--mode",
        mode,
        "--size",
        size,
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    png_hash(&out)
}

fn browser_or_warn() -> Option<PathBuf> {
    let exe = chromium();
    if exe.is_none() {
        eprintln!("WARNING: chromium is not installed: the browser test is skipped");
    }
    exe
}

#[test]
fn the_browser_draws_the_frames_footprint_render_draws() {
    let Some(exe) = browser_or_warn() else { return };
    let served = Served::start(&[]);
    let size = "200x150";
    for pitch in ["40", "5"] {
        let url = format!(
            "http://127.0.0.1:{}/?pitch={pitch}&size={size}&left=ps&right=as&still=1&count=1",
            served.port
        );
        let mut browser = Browser::open(&exe, &url);
        browser.wait_for("document.body.dataset.ready === '1'", 120);
        let hashes = browser.eval("[document.body.dataset.hash0, document.body.dataset.hash1]");
        for (half, mode) in ["ps", "as"].into_iter().enumerate() {
            assert_eq!(
                hashes[half].as_str().unwrap(),
                render_hash(pitch, mode, size),
                "pitch {pitch}, {mode}: the browser's frame differs from footprint render's"
            );
        }
        if pitch == "40" {
            let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("../browser");
            std::fs::create_dir_all(&dir).unwrap();
            let shot = dir.join("footprint-page.png");
            std::fs::write(&shot, browser.screenshot()).unwrap();
            let png = image::open(&shot).expect("the screenshot is a PNG");
            assert!(
                png.width() >= 400,
                "screenshot {}×{}",
                png.width(),
                png.height()
            );
            eprintln!("screenshot: {}", shot.canonicalize().unwrap().display());
        }
    }
}

#[test]
fn a_bad_map_file_shows_the_clis_error_and_keeps_the_map() {
    let Some(exe) = browser_or_warn() else { return };
    let served = Served::start(&[]);
    let url = format!("http://127.0.0.1:{}/?size=120x90", served.port);
    let mut browser = Browser::open(&exe, &url);
    browser.wait_for("document.body.dataset.ready === '1'", 120);
    let before = browser.eval("document.getElementById('map-info').textContent");
    let hash_before = browser.eval("document.body.dataset.hash0");

    // An ASCII grid whose header is cut short, dropped on the page's file input.
    let bad = "ncols 4\nnrows 3\nxllcorner 0\n";
    browser.eval(&format!(
        "(() => {{ const dt = new DataTransfer(); \
         dt.items.add(new File([{bad:?}], 'bad.asc')); \
         const input = document.getElementById('files'); input.files = dt.files; \
         input.dispatchEvent(new Event('change')); return true; }})()"
    ));
    browser.wait_for("document.getElementById('message').textContent !== ''", 30);
    let shown = browser.eval("document.getElementById('message').textContent");
    let shown = shown.as_str().unwrap();

    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("bad.asc"), bad).unwrap();
    let cli = Command::new(env!("CARGO_BIN_EXE_footprint"))
        .current_dir(dir.path())
        .args(["render", "--dem", "bad.asc", "--out", "x.png"])
        .output()
        .unwrap();
    assert_one_line_error(&cli, &["--dem", "bad.asc"], "bad.asc");
    let cli_line = String::from_utf8_lossy(&cli.stderr).trim().to_owned();
    assert_eq!(
        cli_line,
        format!("error: {shown}"),
        "the page and the CLI say the same"
    );

    // The map and the picture stay: the same view drawn again gives the same frame.
    assert_eq!(
        browser.eval("document.getElementById('map-info').textContent"),
        before
    );
    let frames = browser.eval("Number(document.body.dataset.frames)");
    browser.eval("document.getElementById('paper-view').click(); true");
    browser.wait_for(
        &format!("Number(document.body.dataset.frames) > {frames}"),
        30,
    );
    assert_eq!(browser.eval("document.body.dataset.hash0"), hash_before);
}

#[test]
fn serve_refuses_a_port_in_use() {
    let taken = TcpListener::bind((Ipv4Addr::LOCALHOST, 0)).unwrap();
    let port = taken.local_addr().unwrap().port().to_string();
    let o = footprint(&["serve", "--port", &port]);
    assert_one_line_error(&o, &["serve", "--port", &port], &format!("--port {port}"));
    assert!(String::from_utf8_lossy(&o.stderr).contains("in use"));
}

#[test]
fn serve_listens_on_loopback_only() {
    let served = Served::start(&[]);
    let page = String::from_utf8(http_get(served.port, "/")).unwrap();
    assert!(page.contains("<canvas"), "the page: {page:.200}");
    let wasm = http_get(served.port, "/footprint_web.wasm");
    assert!(
        wasm.starts_with(b"\0asm"),
        "not WebAssembly: {} bytes",
        wasm.len()
    );
    // The machine's own non-loopback address (a UDP "connect" sends nothing), if it has one:
    // the server must not answer there.
    let udp = UdpSocket::bind((Ipv4Addr::UNSPECIFIED, 0)).unwrap();
    if udp.connect((Ipv4Addr::new(10, 255, 255, 255), 9)).is_ok() {
        if let Ok(addr) = udp.local_addr() {
            if !addr.ip().is_loopback() && !addr.ip().is_unspecified() {
                assert!(
                    TcpStream::connect_timeout(
                        &(addr.ip(), served.port).into(),
                        Duration::from_secs(2)
                    )
                    .is_err(),
                    "footprint serve answered on {}",
                    addr.ip()
                );
            }
        }
    }
}

#[test]
fn serve_checks_its_map_before_it_listens() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.asc");
    std::fs::write(&bad, "ncols 4\n").unwrap();
    let o = footprint(&["serve", "--port", "0", "--dem", bad.to_str().unwrap()]);
    assert_one_line_error(&o, &["serve", "--dem"], "bad.asc");
}
