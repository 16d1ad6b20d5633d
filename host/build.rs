//! Builds the browser page's WebAssembly (`web/`, `footprint-web` for `wasm32-unknown-unknown`)
//! into `$OUT_DIR/footprint_web.wasm`, which `footprint serve` embeds.
//!
//! A nested `cargo build` in its own target folder (`<target>/wasm-page`), with the workspace's
//! lock file (`--locked`) and none of the outer build's flags (sanitizers, clippy's wrapper).
//! If the target is not installed (`rustup target add wasm32-unknown-unknown`) or the build
//! fails, the host still builds: the file is left empty, a warning says why, and `serve`
//! refuses to start with the same advice. Set `FOOTPRINT_NO_WASM=1` to skip it (then without
//! the warning: `serve` still refuses in one line).

use std::env;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

#[path = "build/wasm_target.rs"]
mod wasm_target;

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    // Read when the script runs, not baked in when it was compiled: a target folder shared
    // with another checkout reuses this binary (same source, same hash), and a compiled-in path
    // would build that checkout's page, or none once it is gone.
    let manifest = PathBuf::from(env::var_os("CARGO_MANIFEST_DIR").expect("cargo sets it"));
    let root = manifest
        .parent()
        .expect("host/ is inside the workspace")
        .to_owned();
    for dir in [
        "web/src",
        "web/Cargo.toml",
        "core/src",
        "scenes/src",
        "maps/src",
        "Cargo.lock",
    ] {
        println!("cargo:rerun-if-changed={}", root.join(dir).display());
    }
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=build/wasm_target.rs");
    println!(
        "cargo:rerun-if-changed={}",
        root.join("web/static").display()
    );
    println!("cargo:rerun-if-env-changed=FOOTPRINT_NO_WASM");
    // The page's files, beside the WebAssembly: copied from web/static, or (in a packaged
    // crate, which has no web/ beside it) a page that says so.
    for name in ["index.html", "app.js", "style.css"] {
        let from = root.join("web/static").join(name);
        let to = out.join(name);
        if fs::copy(&from, &to).is_err() {
            let text = if name == "index.html" {
                "<!doctype html><p>This build of footprint has no browser page: build it from \
                 the repository (web/ beside host/).</p>"
            } else {
                ""
            };
            fs::write(&to, text).expect("write the page's placeholder into OUT_DIR");
        }
    }
    let wasm = out.join("footprint_web.wasm");
    // Skipping the page is a choice (the packaged crate's check, the fuzz targets): `serve`
    // then refuses in one line, and the build does not warn about it.
    let chosen = env::var_os("FOOTPRINT_NO_WASM").is_some();
    let built = if chosen {
        Err("FOOTPRINT_NO_WASM is set".to_owned())
    } else {
        build(&root, &page_target_dir(&out))
    };
    // The one command that adds the target, for `serve`'s refusal and the warning below.
    let add_target = wasm_target::add_target_command(sysroot().as_deref());
    println!("cargo:rustc-env=FOOTPRINT_ADD_WASM_TARGET={add_target}");
    match built {
        Ok(path) => {
            fs::copy(&path, &wasm).expect("copy the page's WebAssembly into OUT_DIR");
            println!("cargo:rustc-env=FOOTPRINT_WASM_MISSING=");
        }
        Err(why) => {
            fs::write(&wasm, b"").expect("write OUT_DIR/footprint_web.wasm");
            // Run again once the target appears: `rustup target add` rewrites the toolchain's
            // list of installed components, so the next build after it builds the page (without
            // this, cargo would keep the empty page until build.rs or the web sources change).
            if let Some(components) = installed_components() {
                println!("cargo:rerun-if-changed={}", components.display());
            }
            // Why, for `serve`'s one-line refusal.
            println!(
                "cargo:rustc-env=FOOTPRINT_WASM_MISSING={}",
                why.replace(['\n', '\r'], " ")
            );
            if !chosen {
                println!(
                    "cargo:warning=footprint serve will not work: the page's WebAssembly was \
                     not built ({why}); run `{add_target}` and build again"
                );
            }
        }
    }
}

/// The nested build's target folder: `wasm-page` in the outer build's target folder
/// (`OUT_DIR` is `<target>/<profile>/build/footprint-host-<hash>/out`), so that the debug and
/// release builds, clippy's and the docs' share one build of the page (each in its own
/// `OUT_DIR` took 180 MB and a few minutes more); `OUT_DIR/wasm-target` if the layout is
/// another. Concurrent outer builds wait for each other on cargo's lock of that folder.
fn page_target_dir(out: &Path) -> PathBuf {
    let is_build = out
        .parent()
        .and_then(Path::parent)
        .and_then(Path::file_name)
        == Some("build".as_ref());
    match out.ancestors().nth(4) {
        Some(target) if is_build && target.is_dir() => target.join("wasm-page"),
        _ => out.join("wasm-target"),
    }
}

/// The toolchain's list of installed components, `<sysroot>/lib/rustlib/components`, which
/// rustup rewrites whenever a target is added; `None` if there is no such file (a toolchain
/// not installed by rustup).
fn installed_components() -> Option<PathBuf> {
    let path = sysroot()?.join("lib/rustlib/components");
    path.is_file().then_some(path)
}

/// The sysroot of the compiler that builds this crate (`rustc --print sysroot`).
fn sysroot() -> Option<PathBuf> {
    let rustc = env::var_os("RUSTC").unwrap_or_else(|| "rustc".into());
    let out = Command::new(rustc)
        .args(["--print", "sysroot"])
        .output()
        .ok()?;
    let sysroot = String::from_utf8(out.stdout).ok()?;
    Some(PathBuf::from(sysroot.trim()))
}

/// Runs the nested build; the path of the `.wasm`, or why it failed.
fn build(root: &Path, target_dir: &Path) -> Result<PathBuf, String> {
    let cargo = env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let mut cmd = Command::new(cargo);
    cmd.current_dir(root)
        .args([
            "build",
            "--release",
            "--locked",
            "--quiet",
            "-p",
            "footprint-web",
            "--target",
            wasm_target::WASM_TARGET,
            "--target-dir",
        ])
        .arg(target_dir)
        // Not the outer build's flags: fuzzing's sanitizers, clippy's driver, a target.
        .env_remove("RUSTFLAGS")
        .env_remove("CARGO_ENCODED_RUSTFLAGS")
        .env_remove("CARGO_BUILD_RUSTFLAGS")
        .env_remove("RUSTC_WRAPPER")
        .env_remove("RUSTC_WORKSPACE_WRAPPER")
        .env_remove("CARGO_BUILD_TARGET")
        .env_remove("CARGO_TARGET_DIR")
        // The page loads fastest without debug info.
        .env("CARGO_PROFILE_RELEASE_DEBUG", "0")
        .env("CARGO_PROFILE_RELEASE_STRIP", "true");
    let output = cmd.output().map_err(|e| format!("cannot run cargo: {e}"))?;
    if !output.status.success() {
        let stderr = String::from_utf8_lossy(&output.stderr);
        let first = stderr
            .lines()
            .find(|l| l.starts_with("error"))
            .unwrap_or("cargo build failed");
        return Err(first.to_owned());
    }
    let path = target_dir.join(format!(
        "{}/release/footprint_web.wasm",
        wasm_target::WASM_TARGET
    ));
    if path.is_file() {
        Ok(path)
    } else {
        Err(format!("{} is missing", path.display()))
    }
}
