//! The command that adds the WebAssembly target to the toolchain that builds the host: shared
//! by `build.rs` (which bakes it into `serve`'s refusal and its own warning) and the host's
//! unit tests (`host/src/lib.rs` includes this file under `cfg(test)`).

use std::path::Path;

/// The target the page is built for.
pub const WASM_TARGET: &str = "wasm32-unknown-unknown";

/// The command that adds [`WASM_TARGET`] to the toolchain whose sysroot is `sysroot`: under
/// rustup (a sysroot in `…/toolchains/NAME`), `rustup +NAME target add …`, which also serves a
/// `cargo +nightly` build (a plain `rustup target add` adds it to the default toolchain only);
/// otherwise (no sysroot known, or a toolchain not installed by rustup) the plain command.
pub fn add_target_command(sysroot: Option<&Path>) -> String {
    let toolchain = sysroot.and_then(|root| {
        let parent = root.parent()?;
        (parent.file_name()? == "toolchains")
            .then(|| root.file_name()?.to_str().map(str::to_owned))
            .flatten()
    });
    match toolchain {
        Some(name) => format!("rustup +{name} target add {WASM_TARGET}"),
        None => format!("rustup target add {WASM_TARGET}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 55, item 4: with `cargo +nightly` the hint named the default toolchain's command.
    #[test]
    fn the_hint_names_the_toolchain_that_builds() {
        let nightly = Path::new("/home/u/.rustup/toolchains/nightly-x86_64-unknown-linux-gnu");
        assert_eq!(
            add_target_command(Some(nightly)),
            "rustup +nightly-x86_64-unknown-linux-gnu target add wasm32-unknown-unknown"
        );
        let stable = Path::new("/root/.rustup/toolchains/stable-x86_64-unknown-linux-gnu");
        assert!(add_target_command(Some(stable)).starts_with("rustup +stable-x86_64"));
        // A distribution's rustc (/usr) or none known: the plain command.
        assert_eq!(
            add_target_command(Some(Path::new("/usr"))),
            "rustup target add wasm32-unknown-unknown"
        );
        assert_eq!(
            add_target_command(None),
            "rustup target add wasm32-unknown-unknown"
        );
    }
}
