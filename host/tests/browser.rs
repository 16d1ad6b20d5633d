//! `footprint serve` and the page in a real headless browser (Debian's `chromium`, driven over
//! the DevTools protocol): the frames the WebAssembly core draws in the browser hash to the
//! same FNV-1a-64 as `footprint render`'s, a bad map file shows the CLI's one-line error and
//! keeps the map, and the server refuses a port in use and listens on loopback only.
//!
//! Without `chromium` on the PATH the browser tests print a warning and pass (`.ci/run`
//! installs it). The page's screenshot is saved as `target/browser/footprint-page.png`.

use std::net::{Ipv4Addr, TcpListener, TcpStream, UdpSocket};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

use base64::Engine as _;

mod common;

use common::browser::{chromium, http_get, page_or_warn, Browser, Served};
use common::{assert_one_line_error, footprint, write_asc};

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
    render_hash_of(&[
        "--view", "paper", "--pitch", pitch, "--mode", mode, "--size", size,
    ])
}

/// The hash of the PNG `footprint render ARGS --out …` writes.
fn render_hash_of(args: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("frame.png");
    let mut all = vec!["render"];
    all.extend_from_slice(args);
    all.extend(["--out", out.to_str().unwrap()]);
    let o = footprint(&all);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    png_hash(&out)
}

fn browser_or_warn() -> Option<PathBuf> {
    let exe = chromium();
    if exe.is_none() {
        eprintln!("WARNING: chromium is not installed: the browser test is skipped");
    }
    exe.filter(|_| page_or_warn())
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
    choose_file(&mut browser, "files", "bad.asc", bad.as_bytes());
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
    if !page_or_warn() {
        return;
    }
    let taken = TcpListener::bind((Ipv4Addr::LOCALHOST, 0)).unwrap();
    let port = taken.local_addr().unwrap().port().to_string();
    let o = footprint(&["serve", "--port", &port]);
    assert_one_line_error(&o, &["serve", "--port", &port], &format!("--port {port}"));
    assert!(String::from_utf8_lossy(&o.stderr).contains("in use"));
}

#[test]
fn serve_listens_on_loopback_only() {
    if !page_or_warn() {
        return;
    }
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

/// Puts a file named `name` holding `bytes` into the page's file input `input`, as a person
/// choosing it would (the input's `change` event fires).
fn choose_file(browser: &mut Browser, input: &str, name: &str, bytes: &[u8]) {
    let data = base64::engine::general_purpose::STANDARD.encode(bytes);
    browser.eval(&format!(
        "(() => {{ const bytes = Uint8Array.from(atob('{data}'), (c) => c.charCodeAt(0)); \
         const dt = new DataTransfer(); dt.items.add(new File([bytes], '{name}')); \
         const input = document.getElementById('{input}'); input.files = dt.files; \
         input.dispatchEvent(new Event('change')); return true; }})()"
    ));
}

/// A PNG of `img` as bytes.
fn png_bytes<P: image::PixelWithColorType>(img: &image::ImageBuffer<P, Vec<P::Subpixel>>) -> Vec<u8>
where
    [P::Subpixel]: image::EncodableLayout,
{
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).unwrap();
    out.into_inner()
}

#[test]
fn a_png_height_map_and_its_colour_map_load_from_the_two_pickers() {
    let Some(exe) = browser_or_warn() else { return };
    let served = Served::start(&[]);
    let url = format!("http://127.0.0.1:{}/?size=120x90", served.port);
    let mut browser = Browser::open(&exe, &url);
    browser.wait_for("document.body.dataset.ready === '1'", 120);
    let heights = image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::from_fn(48, 32, |x, y| {
        image::Luma([((x * 37 + y * 11) % 500) as u16])
    });
    let colors =
        image::RgbImage::from_fn(48, 32, |x, y| image::Rgb([x as u8 * 5, y as u8 * 7, 90]));
    // The colour map first: it waits for a height map, then the pair loads.
    choose_file(&mut browser, "color-file", "tint.png", &png_bytes(&colors));
    choose_file(&mut browser, "files", "height.png", &png_bytes(&heights));
    browser.wait_for(
        "document.getElementById('map-info').textContent.includes('48×32')",
        30,
    );
    let info = browser.eval("document.getElementById('map-info').textContent");
    let info = info.as_str().unwrap();
    assert!(
        info.contains("height.png") && info.contains("tint.png"),
        "{info}"
    );
    assert_eq!(
        browser.eval("document.getElementById('message').textContent"),
        ""
    );
}

/// The map is read once, when the server starts (issue 28): an empty standard input or a
/// folder is refused then, naming `--dem`.
#[test]
fn serve_refuses_a_map_it_cannot_read() {
    let o = footprint(&["serve", "--port", "0", "--dem", "-"]);
    assert_one_line_error(&o, &["serve", "--dem", "-"], "--dem -");
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path().to_str().unwrap();
    let o = footprint(&["serve", "--port", "0", "--dem", d]);
    assert_one_line_error(&o, &["serve", "--dem", d], "--dem");
}

#[test]
fn the_page_opens_the_map_serve_was_given() {
    let Some(exe) = browser_or_warn() else { return };
    let dir = tempfile::tempdir().unwrap();
    let grid = dir.path().join("ridge.asc");
    write_asc(&grid, (40, 30), 10, |x, y| (x * 5 + y * 2) % 70);
    let served = Served::start(&["--dem", grid.to_str().unwrap()]);
    let url = format!("http://127.0.0.1:{}/?size=120x90&still=1", served.port);
    let mut browser = Browser::open(&exe, &url);
    browser.wait_for("document.body.dataset.ready === '1'", 120);
    let info = browser.eval("document.getElementById('map-info').textContent");
    let info = info.as_str().unwrap();
    assert!(
        info.contains("ridge.asc") && info.contains("40×30"),
        "{info}"
    );
    assert_eq!(browser.eval("document.body.dataset.message"), "");
    // Issue 55, item 5: the map opens in the view `render --dem` takes of it (the map itself),
    // not the paper's view of its centre (a wallpaper of its mirrored copies).
    let hashes = browser.eval("[document.body.dataset.hash0, document.body.dataset.hash1]");
    for (half, mode) in ["ps", "as"].into_iter().enumerate() {
        let dem = grid.to_str().unwrap();
        assert_eq!(
            hashes[half].as_str().unwrap(),
            render_hash_of(&["--dem", dem, "--mode", mode, "--size", "120x90"]),
            "{mode}: the page's first frame of a served map differs from `render --dem`'s"
        );
    }
}

#[test]
fn serve_refuses_a_built_in_terrain_of_a_bad_size() {
    let o = footprint(&["serve", "--port", "0", "--terrain-size", "8"]);
    assert_one_line_error(
        &o,
        &["serve", "--terrain-size", "8"],
        "--terrain-size 8: must be 16..=65536",
    );
}

/// The texts of the page's table of numbers, row by row: the label, then each cell.
fn stats_rows(browser: &mut Browser) -> Vec<Vec<String>> {
    let rows = browser.eval(
        "[...document.querySelectorAll('#stats tr')].map((r) => [...r.children].map((c) => c.textContent))",
    );
    serde_json::from_value(rows).unwrap()
}

/// The row whose label contains `label`: its cells' texts.
fn row<'a>(rows: &'a [Vec<String>], label: &str) -> &'a [String] {
    let r = rows
        .iter()
        .find(|r| r[0].contains(label))
        .unwrap_or_else(|| panic!("no row labelled {label:?} in {rows:?}"));
    &r[1..]
}

/// The page's rates (issue 38, item 6): the frames it delivered in the last second (both
/// halves drawn), and each half's render time, each labelled as such, and never `Infinity` or
/// `NaN`, also when the clock stands still (headless Chromium's virtual time advances only while
/// the page is idle: every render then takes 0 ms, and the page used to print 1000 / 0 =
/// `Infinity` frames per second).
#[test]
fn the_page_shows_the_frames_it_delivers_and_each_halfs_render_time() {
    let Some(exe) = browser_or_warn() else { return };
    let served = Served::start(&[]);
    let url = format!("http://127.0.0.1:{}/?size=120x90", served.port);
    let mut browser = Browser::open(&exe, &url);
    browser.wait_for("document.body.dataset.ready === '1'", 120);
    let number = |s: &str| -> f64 {
        assert!(
            !s.contains("Infinity") && !s.contains("NaN"),
            "a rate reads {s:?}"
        );
        s.replace(',', "")
            .parse()
            .unwrap_or_else(|_| panic!("not a number: {s:?}"))
    };

    // Flying the paper's path, the page delivers frames: some in the last second, each half
    // taking a positive time.
    browser.eval("document.getElementById('fly').click(); true");
    browser.wait_for("Number(document.body.dataset.frames) > 20", 120);
    let rows = stats_rows(&mut browser);
    let delivered = row(&rows, "frames delivered in the last second");
    assert_eq!(delivered.len(), 1, "one rate for the page: {delivered:?}");
    let fps = number(&delivered[0]);
    assert!(fps >= 1.0 && fps.fract() == 0.0, "delivered {fps}");
    let times = row(&rows, "render time of this half");
    assert_eq!(times.len(), 2, "a time per half: {times:?}");
    for t in times {
        assert!(number(t) > 0.0, "render time {t:?}");
    }
    assert!(
        !rows.iter().any(|r| r[0].contains("frames per second")),
        "no rate derived from one half's time: {rows:?}"
    );

    // Virtual time: it stands still while the page runs, so renders take 0 ms; nothing is
    // divided by them.
    browser.call(
        "Emulation.setVirtualTimePolicy",
        serde_json::json!({ "policy": "advance" }),
    );
    browser.call("Page.reload", serde_json::json!({}));
    browser.wait_for("document.body.dataset.ready === '1'", 120);
    let rows = stats_rows(&mut browser);
    for t in row(&rows, "render time of this half") {
        assert_eq!(number(t), 0.0, "the clock stands still, yet {t:?}");
    }
    number(&row(&rows, "frames delivered in the last second")[0]);
    let all = browser.eval("document.getElementById('stats').textContent");
    let all = all.as_str().unwrap();
    assert!(
        !all.contains("Infinity") && !all.contains("NaN"),
        "the page's numbers: {all}"
    );
}
