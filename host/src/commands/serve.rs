//! `footprint serve`: the browser page (`web/`), from 127.0.0.1 only.
//!
//! The page, its script and the WebAssembly core are built into the binary (the `.wasm` by
//! `host/build.rs`); a `--dem` map (and its `--color`) is checked here with the CLI's readers,
//! then served as the bytes the user gave, for the page to read with the same readers compiled
//! to WebAssembly.

use std::net::{Ipv4Addr, SocketAddr, TcpListener};
use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use clap::Args;
use tiny_http::{Header, Response, Server};

use crate::map::{self, LoadOptions};

/// The page's WebAssembly core, built by `host/build.rs` (empty if it could not be built).
const WASM: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/footprint_web.wasm"));
// Copied from web/static by host/build.rs, so that the packaged crate builds too.
const INDEX: &str = include_str!(concat!(env!("OUT_DIR"), "/index.html"));
const SCRIPT: &str = include_str!(concat!(env!("OUT_DIR"), "/app.js"));
const STYLE: &str = include_str!(concat!(env!("OUT_DIR"), "/style.css"));

/// `footprint serve`.
#[derive(Args, Debug)]
pub struct ServeArgs {
    /// The port on 127.0.0.1 (0: any free port; the address is printed).
    #[arg(long, default_value_t = 8080)]
    pub port: u16,
    /// A height map for the page to open instead of the built-in terrain (.png, .asc, .hgt,
    /// .tif), read in the browser by the CLI's readers.
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
    let addr = SocketAddr::from((Ipv4Addr::LOCALHOST, args.port));
    let listener = TcpListener::bind(addr).map_err(|e| match e.kind() {
        std::io::ErrorKind::AddrInUse => {
            anyhow::anyhow!("--port {}: already in use on 127.0.0.1", args.port)
        }
        _ => anyhow::anyhow!("--port {}: cannot listen on 127.0.0.1 ({e})", args.port),
    })?;
    let port = listener.local_addr()?.port();
    let server =
        Server::from_listener(listener, None).map_err(|e| anyhow::anyhow!("--port {port}: {e}"))?;
    println!("serving the page at http://127.0.0.1:{port}/ (Ctrl-C stops)");
    for request in server.incoming_requests() {
        let path = request.url().split('?').next().unwrap_or("/").to_owned();
        let asset = match path.as_str() {
            "/" | "/index.html" => Some(text(INDEX, "text/html; charset=utf-8")),
            "/app.js" => Some(text(SCRIPT, "text/javascript; charset=utf-8")),
            "/style.css" => Some(text(STYLE, "text/css; charset=utf-8")),
            "/footprint_web.wasm" => Some(Asset {
                bytes: WASM.to_vec(),
                kind: "application/wasm",
            }),
            "/map.json" => Some(text(&map.json, "application/json")),
            _ => map
                .files
                .iter()
                .find(|(url, _)| *url == path)
                .map(|(_, file)| Asset {
                    bytes: std::fs::read(file).unwrap_or_default(),
                    kind: "application/octet-stream",
                }),
        };
        let response = match asset {
            // A Content-Length, never chunked: the page's fetches and simple clients alike.
            Some(a) => Response::from_data(a.bytes)
                .with_chunked_threshold(usize::MAX)
                .with_header(header("Content-Type", a.kind)),
            None => Response::from_data(b"not found".to_vec()).with_status_code(404),
        };
        // A client that went away is no reason to stop serving.
        let _ = request.respond(response.with_header(header("Cache-Control", "no-store")));
    }
    Ok(())
}

/// The page's map: `map.json` (the built-in terrain's seed and side, or the URLs and names of
/// the files) and the files by URL.
struct MapFiles {
    json: String,
    files: Vec<(String, PathBuf)>,
}

/// Checks `--dem` (and `--color`) with the CLI's readers and lists them for the page.
fn map_files(args: &ServeArgs) -> Result<MapFiles> {
    let Some(dem) = &args.dem else {
        map::procedural::check_size(args.terrain_size).map_err(anyhow::Error::msg)?;
        let json = serde_json::json!({ "seed": args.seed, "terrain_size": args.terrain_size });
        return Ok(MapFiles {
            json: json.to_string(),
            files: Vec::new(),
        });
    };
    // The page fetches the files when it opens, so they must be files that can be read again.
    for (option, path) in [("--dem", Some(dem)), ("--color", args.color.as_ref())] {
        if let Some(p) = path.filter(|p| !p.is_file()) {
            bail!(
                "{option} {}: serve needs a regular file (the page reads it again when it opens)",
                p.display()
            );
        }
    }
    map::load(
        dem,
        &LoadOptions {
            color: args.color.as_deref(),
            ..LoadOptions::default()
        },
    )?;
    let name = |p: &Path| -> Result<String> {
        p.file_name()
            .and_then(|n| n.to_str())
            .map(str::to_owned)
            .with_context(|| format!("--dem {:?}: the page needs a file name in UTF-8", p))
    };
    let mut files = vec![("/map/height".to_owned(), dem.clone())];
    let mut json = serde_json::json!({ "height": { "url": "/map/height", "name": name(dem)? } });
    if let Some(color) = &args.color {
        files.push(("/map/color".to_owned(), color.clone()));
        json["color"] = serde_json::json!({ "url": "/map/color", "name": name(color)? });
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

fn header(field: &str, value: &str) -> Header {
    Header::from_bytes(field.as_bytes(), value.as_bytes()).expect("a valid ASCII header")
}
