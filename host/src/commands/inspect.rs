//! `footprint inspect`: the paper's diagnostic pictures for a view and a mode.

use std::path::PathBuf;

use anyhow::{bail, Result};
use clap::Args;

use crate::args::OutputFormat;
use crate::experiment::inspect;
use crate::output::Target;
use crate::parallel::Mode;
use crate::report::png::write_png;
use crate::view_args::{CameraArgs, MapArgs, ViewArg};
use footprint_core::prelude::Options;

/// A pixel `ROW,COL`, counted from the top-left.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelArg {
    /// Row from the top.
    pub row: usize,
    /// Column from the left.
    pub col: usize,
}

impl std::str::FromStr for PixelArg {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let err = || format!("pixel {s:?}: expected ROW,COL, e.g. 200,150");
        let (r, c) = s.split_once(',').ok_or_else(err)?;
        Ok(PixelArg {
            row: r.trim().parse().map_err(|_| err())?,
            col: c.trim().parse().map_err(|_| err())?,
        })
    }
}

/// `footprint inspect`.
#[derive(Args, Debug)]
pub struct InspectArgs {
    #[command(flatten)]
    /// The map.
    pub map: MapArgs,
    #[command(flatten)]
    /// The camera.
    pub camera: CameraArgs,
    /// The mode to inspect.
    #[arg(long, default_value = "as")]
    pub mode: Mode,
    /// Fig. 5: a tiny window magnified, PS on the left and --mode on the right.
    #[arg(long)]
    pub zoom: bool,
    /// How much smaller the zoom window's field of view is than --fov.
    #[arg(long, default_value_t = 16.0)]
    pub zoom_factor: f64,
    /// Fig. 13: the samples of one pixel, each filling a band as tall as its weight.
    #[arg(long, value_name = "ROW,COL")]
    pub pixel: Option<PixelArg>,
    /// Fig. 9: the ground under the frame — sampled blue, visible unsampled red, hidden green.
    #[arg(long)]
    pub footprint: bool,
    /// One pixel's footprint in both axes, seen from above (north up): the column's two
    /// vertical planes (red) bound it across, where its two row rays meet the ground (black)
    /// bound it along; the cells `as2` weighs across that wedge are filled orange, and the
    /// voxels --mode samples on the column's centre line (blue dashes) are framed in blue
    /// (`as-exact`'s when --mode is `as2`).
    #[arg(long, value_name = "ROW,COL")]
    pub wedge: Option<PixelArg>,
    /// Output PNG (with several pictures, `-zoom`, `-pixel`, `-footprint`, `-wedge` are added
    /// to its stem); `-` is standard output (one picture).
    #[arg(long, value_name = "FILE.png")]
    pub out: PathBuf,
    #[command(flatten)]
    /// `--json`.
    pub format: OutputFormat,
}

/// Runs `footprint inspect`.
pub fn inspect(args: &InspectArgs) -> Result<()> {
    let wanted = [
        args.zoom,
        args.pixel.is_some(),
        args.footprint,
        args.wedge.is_some(),
    ];
    let n = wanted.iter().filter(|&&w| w).count();
    if n == 0 {
        bail!("inspect: give --zoom, --pixel ROW,COL, --footprint or --wedge ROW,COL");
    }
    if n > 1 && !matches!(crate::output::target(&args.out), Ok(Target::Replace(_))) {
        bail!(
            "--out {}: several pictures go to files named after it (-zoom, -pixel, -footprint, \
             -wedge added to its stem); give a file name, or one of --zoom, --pixel, \
             --footprint, --wedge",
            crate::output::shown(&args.out)
        );
    }
    let path_for = |suffix: &str| -> PathBuf {
        if n == 1 {
            return args.out.clone();
        }
        let stem = args
            .out
            .file_stem()
            .map_or("inspect".into(), |s| s.to_string_lossy().into_owned());
        args.out.with_file_name(format!("{stem}-{suffix}.png"))
    };
    let view = args.camera.load(&args.map, ViewArg::Paper)?;
    let (w, h) = (view.camera.width(), view.camera.height());
    for (flag, p) in [("--pixel", args.pixel), ("--wedge", args.wedge)] {
        if let Some(p) = p.filter(|p| p.row >= h || p.col >= w) {
            bail!("{flag} {},{}: outside the {w}x{h} image", p.row, p.col);
        }
    }
    // The paper's pictures walk the pyramid, in the view's projection.
    let pictures = Options {
        lod: true,
        ..view.options
    };
    let mut json = serde_json::Map::new();
    // Each picture as it is written: its file and size, printed as `render` prints its PNG.
    let mut wrote = Vec::new();
    let written = |picture: &'static str, pic: &inspect::Picture| -> Result<Written> {
        let out = path_for(picture);
        write_png(&out, pic.width, pic.height, &pic.pixels)?;
        Ok(Written {
            picture,
            out: crate::output::shown(&out),
            width: pic.width,
            height: pic.height,
        })
    };
    if args.zoom {
        let pic = inspect::zoom(
            view.camera.params(),
            &view.pyramid,
            pictures,
            args.mode,
            args.zoom_factor,
            48,
            6,
        )?;
        wrote.push(written("zoom", &pic)?);
    }
    if let Some(p) = args.pixel {
        let (samples, color, pic) = inspect::pixel(
            &view.camera,
            &view.pyramid,
            pictures,
            args.mode,
            p.row,
            p.col,
            (64, 256),
        )?;
        wrote.push(written("pixel", &pic)?);
        json.insert(
            "pixel".into(),
            serde_json::json!({
                "row": p.row, "col": p.col, "mode": args.mode.to_string(),
                "color": format!("#{:02x}{:02x}{:02x}", color.r, color.g, color.b),
                "samples": samples,
            }),
        );
        if !args.format.json {
            crate::outln!(
                "pixel {},{} ({}): {} samples, colour #{:02x}{:02x}{:02x}",
                p.row,
                p.col,
                args.mode,
                samples.len(),
                color.r,
                color.g,
                color.b
            )?;
        }
    }
    if args.footprint {
        let (counts, pic) =
            inspect::footprint(&view.camera, &view.pyramid, pictures, args.mode, 1024)?;
        wrote.push(written("footprint", &pic)?);
        json.insert("footprint".into(), serde_json::to_value(counts)?);
        if !args.format.json {
            crate::outln!(
                "footprint ({}): {} sampled, {} visible but unsampled, {} hidden",
                args.mode,
                counts.sampled,
                counts.unsampled,
                counts.hidden
            )?;
        }
    }
    if let Some(p) = args.wedge {
        let (summary, pic) = inspect::wedge(
            &view.camera,
            &view.pyramid,
            pictures,
            args.mode,
            p.row,
            p.col,
            720,
        )?;
        wrote.push(written("wedge", &pic)?);
        if !args.format.json {
            let ground = |m: Option<f64>| {
                m.map_or("nowhere within the far distance".into(), |m| {
                    format!("{m:.0} m")
                })
            };
            crate::outln!(
                "wedge {},{}: as2 weighs {} cells across at {} hits (level {}..={}), {} samples \
                 {} on the centre line; the wedge is {:.2} voxels wide at the first hit, {:.2} at \
                 the last; the row rays meet the ground at {} and {}; {}x{} picture, {} pixels \
                 per voxel",
                p.row,
                p.col,
                summary.as2_cells,
                summary.as2_hits,
                summary.levels.0,
                summary.levels.1,
                summary.line_mode,
                summary.line_cells,
                summary.across_near,
                summary.across_far,
                ground(summary.near_m),
                ground(summary.far_m),
                summary.width,
                summary.height,
                (summary.pixels_per_voxel * 100.0).round() / 100.0
            )?;
        }
        json.insert("wedge".into(), serde_json::to_value(summary)?);
    }
    if args.format.json {
        json.insert("wrote".into(), serde_json::to_value(&wrote)?);
        crate::outln!("{}", serde_json::Value::Object(json))?;
    } else {
        for w in &wrote {
            crate::outln!("wrote {}: {}x{}, {}", w.out, w.width, w.height, w.picture)?;
        }
    }
    view.warn_mirrored(&args.camera)
}

/// A picture `inspect` wrote (the JSON's `wrote`).
#[derive(Debug, serde::Serialize)]
struct Written {
    /// Which picture: `zoom`, `pixel`, `footprint` or `wedge`.
    picture: &'static str,
    /// Its file, as given (`-`: standard output).
    out: String,
    /// Its size, pixels.
    width: u32,
    height: u32,
}
