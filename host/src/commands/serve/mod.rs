//! `footprint serve`: the browser page (`web/`), from 127.0.0.1 only.
//!
//! The page, its script and the WebAssembly core are built into the binary (the `.wasm` by
//! `host/build.rs`); a `--dem` map (and its `--color`) is read once, when the server starts,
//! checked there with the CLI's readers, and served from memory as the bytes the user gave,
//! for the page to read with the same readers compiled to WebAssembly.
//!
//! The server holds under hostile or broken clients: one thread waits on every connection at
//! once (`poll(2)`, non-blocking sockets; `server.rs`), so a client that sends, reads or does
//! nothing holds no one but itself. A request's head must arrive whole within
//! [`HEAD_DEADLINE`] and be at most [`MAX_HEAD`] bytes (431 otherwise); a client must read an
//! answer at [`MIN_RATE`] or more over each [`RATE_WINDOW`] or it is dropped; at most
//! [`MAX_CONNECTIONS`] are kept, and a new connection takes the place of the oldest one
//! that is idle or half-sent, so a complete request is refused (503) only when every place
//! is writing an answer. Only GET and HEAD are answered (405 otherwise), and only to requests
//! whose `Host` is a loopback name (`localhost`, `127.0.0.1`, `[::1]`, with any port; 403
//! otherwise, and for an HTTP/1.0 request without `Host`), so a page on another site that
//! rebinds its DNS name to 127.0.0.1 cannot read the user's map. Requests are parsed by
//! `httparse` (`http.rs`).

mod http;
mod server;

use std::net::{Ipv4Addr, SocketAddr, TcpListener};
use std::path::{Path, PathBuf};
use std::time::Duration;

use anyhow::{bail, Context, Result};
use clap::Args;

use crate::map::{self, LoadOptions};

/// The page's WebAssembly core, built by `host/build.rs` (empty if it could not be built).
const WASM: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/footprint_web.wasm"));
// Copied from web/static by host/build.rs, so that the packaged crate builds too.
const INDEX: &str = include_str!(concat!(env!("OUT_DIR"), "/index.html"));
const SCRIPT: &str = include_str!(concat!(env!("OUT_DIR"), "/app.js"));
const STYLE: &str = include_str!(concat!(env!("OUT_DIR"), "/style.css"));

/// Connections kept at once. A new one takes the place of the oldest that is not being
/// answered (idle, half-sent, or closing); only when all of them are being answered is it
/// answered 503 and closed.
pub const MAX_CONNECTIONS: usize = 512;
/// How long a request's head may take to arrive, all of it, from the moment the connection
/// was accepted or its previous answer written (so also how long a kept-alive connection may
/// stay idle).
pub const HEAD_DEADLINE: Duration = Duration::from_secs(5);
/// The slowest a client may read an answer, bytes a second on average over the last
/// [`RATE_WINDOW`]; a slower one is dropped.
pub const MIN_RATE: usize = 16 * 1024;
/// The span over which [`MIN_RATE`] is measured, checked every second from the answer's
/// start: a client that has taken less than `MIN_RATE × RATE_WINDOW` bytes of an unfinished
/// answer in its first `RATE_WINDOW`, or in any later one, is dropped.
pub const RATE_WINDOW: Duration = Duration::from_secs(8);
/// How long a connection that is closed after its answer still reads what the client sends
/// (so that the client's unread bytes do not reset the connection before it has the answer).
pub const LINGER: Duration = Duration::from_secs(2);
/// The largest request head (request line and headers, up to and with the blank line),
/// bytes: a head of exactly this size is answered, one byte more gets 431.
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
            "serve: the page needs the WebAssembly target, once: `{}`, then `cargo run \
             --release -- serve` again",
            env!("FOOTPRINT_ADD_WASM_TARGET")
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
    let site = Site { assets };
    let addr = SocketAddr::from((Ipv4Addr::LOCALHOST, args.port));
    let listener = TcpListener::bind(addr).map_err(|e| match e.kind() {
        std::io::ErrorKind::AddrInUse => {
            anyhow::anyhow!("--port {}: already in use on 127.0.0.1", args.port)
        }
        _ => anyhow::anyhow!("--port {}: cannot listen on 127.0.0.1 ({e})", args.port),
    })?;
    server::prepare(&listener)?;
    let port = listener.local_addr()?.port();
    crate::outln!("serving the page at http://127.0.0.1:{port}/ (Ctrl-C stops)")?;
    crate::console::flush()?;
    server::run(&listener, &site)?;
    Ok(())
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
    if map::baked::is_baked_bytes(dem, &dem_bytes) {
        if args.color.is_some() {
            anyhow::bail!(
                "--color: {} is a baked map, which has its colours",
                dem.display()
            );
        }
        // The page reads it with the same code (`baked::from_bytes`), every level checked.
        map::baked::from_bytes(dem, &dem_bytes)
            .with_context(|| format!("--dem {}", crate::output::shown(dem)))?;
    } else {
        map::load(
            dem,
            &LoadOptions {
                color: args.color.as_deref(),
                in_memory: &in_memory,
                ..LoadOptions::default()
            },
        )
        .with_context(|| format!("--dem {}", crate::output::shown(dem)))?;
    }
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
