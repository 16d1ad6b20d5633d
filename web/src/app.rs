//! The page's state: one map, one camera, two halves (see the crate documentation).

use std::path::Path;

use footprint_core::prelude::{
    Camera, CameraParams, Frame, HeightFilter, NoCost, Options, Projection, Tally, Terrain,
};
use footprint_core::Rgb;
use footprint_maps::{memory, LoadOptions};
use footprint_maps::{procedural, Map, Pyramid};
use footprint_scenes::counted::{count, image_hash, render_with, Mode, ParseModeError};
use footprint_scenes::flight::{self, bin, luminance};
use footprint_scenes::view::{self, Tables};

/// The memory budget in the browser: a 32-bit WebAssembly memory holds at most 4 GiB, and a
/// tab gets less. A map and its pyramid above it are refused with the CLI's one-line error.
pub const BUDGET_BYTES: u64 = 1 << 30;

/// The built-in terrain's seed and side when the page opens (the CLI's defaults).
pub const DEFAULT_SEED: u64 = 1;
/// The built-in terrain's side, voxels.
pub const DEFAULT_SIZE: u32 = procedural::DEFAULT_SIZE;

/// The counters of one frame (Sect. 6), from the counted render with the visibility pass.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Counters {
    /// Steps from the first hit (`L`).
    pub l: u64,
    /// Terrain pixels (`P`).
    pub p: u64,
    /// Distinct voxels sampled (`M`).
    pub m: u64,
    /// Visible voxels (`V`, the exact pass).
    pub v: u64,
    /// Hits.
    pub hits: u64,
    /// Coverage `M/V`.
    pub coverage: f64,
    /// Sampled voxels that are hidden.
    pub hidden: u64,
    /// Visible voxels not sampled.
    pub missed: u64,
}

impl Counters {
    /// The counters of a frame's tally and its hidden and missed voxels.
    fn new(t: &Tally, hidden: u64, missed: u64) -> Self {
        Self {
            l: t.l,
            p: t.p,
            m: t.m,
            v: t.v,
            hits: t.hits,
            coverage: t.coverage(),
            hidden,
            missed,
        }
    }
}

/// One half of the canvas: a mode, its last frame, and how much it flickered.
#[derive(Debug)]
pub struct Half {
    mode: Mode,
    /// The last frame, RGBA row-major from the top (what a canvas `ImageData` takes).
    rgba: Vec<u8>,
    /// The last frame's 8-bit luminance per pixel, for the flicker meter.
    luma: Vec<u8>,
    /// Whether `luma` holds a frame of the current size.
    has_previous: bool,
    /// The FNV-1a-64 of the last frame's RGB bytes (the firmware's and the CLI's hash).
    hash: u64,
    /// Mean |ΔY| against the frame before, and the pixels that changed by 6–60 levels.
    mean_dy: f64,
    changed_6_60: u64,
    counters: Counters,
}

impl Half {
    fn new(mode: Mode) -> Self {
        Self {
            mode,
            rgba: Vec::new(),
            luma: Vec::new(),
            has_previous: false,
            hash: 0,
            mean_dy: 0.0,
            changed_6_60: 0,
            counters: Counters::default(),
        }
    }

    /// The mode.
    pub fn mode(&self) -> Mode {
        self.mode
    }
    /// The last frame, RGBA.
    pub fn rgba(&self) -> &[u8] {
        &self.rgba
    }
    /// The FNV-1a-64 of the last frame's RGB bytes, row-major from the top.
    pub fn hash(&self) -> u64 {
        self.hash
    }
    /// Mean |ΔY| (8-bit luminance) between the last two frames; 0 after the first.
    pub fn mean_dy(&self) -> f64 {
        self.mean_dy
    }
    /// Pixels whose luminance changed by 6–60 levels between the last two frames (Table 6).
    pub fn changed_6_60(&self) -> u64 {
        self.changed_6_60
    }
    /// The counters of the last [`App::count`].
    pub fn counters(&self) -> Counters {
        self.counters
    }

    /// Takes a new frame: RGBA, hash and the flicker against the frame before.
    fn take(&mut self, image: &[Rgb]) {
        self.rgba.clear();
        self.rgba
            .extend(image.iter().flat_map(|c| [c.r, c.g, c.b, 255]));
        self.hash = image_hash(image);
        let luma: Vec<u8> = image.iter().map(|&c| luminance(c)).collect();
        if self.has_previous && self.luma.len() == luma.len() && !luma.is_empty() {
            let mut sum = 0u64;
            let mut changed = 0u64;
            for (a, b) in self.luma.iter().zip(&luma) {
                let d = a.abs_diff(*b);
                sum += u64::from(d);
                changed += u64::from(bin(d) == 6);
            }
            self.mean_dy = sum as f64 / luma.len() as f64;
            self.changed_6_60 = changed;
        } else {
            self.mean_dy = 0.0;
            self.changed_6_60 = 0;
        }
        self.luma = luma;
        self.has_previous = true;
    }
}

/// The page's state.
#[derive(Debug)]
pub struct App {
    pyramid: Pyramid,
    params: CameraParams,
    options: Options,
    halves: [Half; 2],
}

impl App {
    /// The page as it opens: the built-in terrain ([`DEFAULT_SEED`], [`DEFAULT_SIZE`]) seen by
    /// the paper's camera at pitch 20°, 400×400, in the exact projection (the CLI's `render`
    /// defaults), PS left and AS right.
    pub fn new() -> Result<Self, String> {
        memory::set_budget(BUDGET_BYTES);
        let pyramid = build(procedural(DEFAULT_SEED, DEFAULT_SIZE))?;
        let options = Options {
            projection: Projection::Exact,
            // `render`'s `--surface auto`: the map's own.
            surface: pyramid.map().surface,
            ..Options::default()
        };
        let camera = view::paper_camera(&pyramid, 20.0, 400, 400, options)
            .map_err(|e| format!("camera: {e}"))?;
        Ok(Self {
            pyramid,
            params: *camera.params(),
            options,
            halves: [Half::new(Mode::Ps), Half::new(Mode::As)],
        })
    }

    /// The map.
    pub fn map(&self) -> &Map {
        self.pyramid.map()
    }

    /// The camera.
    pub fn params(&self) -> &CameraParams {
        &self.params
    }

    /// Half `i` (0 left, 1 right), if there is one.
    pub fn half(&self, i: usize) -> Option<&Half> {
        self.halves.get(i)
    }

    /// Replaces the map by the built-in terrain of `seed` and `size`, seen by the paper's camera
    /// at the current pitch and size (the page's opening view). On error the map stays as it
    /// was.
    pub fn load_builtin(&mut self, seed: u64, size: u32) -> Result<(), String> {
        procedural::check_size(size)?;
        memory::check(
            memory::builtin_map_bytes(size, size),
            &format!("--terrain-size {size}"),
            "the map and its pyramid",
        )
        .map_err(|e| e.to_string())?;
        let pyramid = build(procedural(seed, size))?;
        let camera = view::paper_camera(
            &pyramid,
            self.params.pitch_deg,
            self.params.width,
            self.params.height,
            self.options,
        )
        .map_err(|e| format!("camera: {e}"))?;
        self.replace(pyramid, camera);
        Ok(())
    }

    /// Replaces the map by the files the user dropped: a height map (`.png`, `.asc`, `.hgt`,
    /// `.tif`, `.fpmap`) named `name`, and optionally a colour PNG of the same size, read by the
    /// CLI's readers with the CLI's limits and one-line errors, seen by the view `footprint
    /// render --dem` takes of it ([`App::overview`]): the map itself, not the paper's view of its
    /// centre (on a small map, a wallpaper of its mirrored copies). On error the map stays as it
    /// was.
    pub fn load_files(
        &mut self,
        name: &str,
        bytes: &[u8],
        color: Option<(&str, &[u8])>,
    ) -> Result<(), String> {
        let path = Path::new(name);
        if footprint_maps::baked::is_baked_bytes(path, bytes) {
            if color.is_some() {
                return Err(format!("{name} is a baked map, which has its colours"));
            }
            let (pyramid, _) =
                footprint_maps::baked::from_bytes(path, bytes).map_err(|e| e.to_string())?;
            return self.replace_overview(pyramid);
        }
        let color_path = color.map(|(n, _)| Path::new(n));
        let mut files = vec![(path, bytes)];
        if let Some((n, b)) = color {
            files.push((Path::new(n), b));
        }
        let loaded = footprint_maps::load(
            path,
            &LoadOptions {
                color: color_path,
                in_memory: &files,
                ..LoadOptions::default()
            },
        )
        .map_err(|e| e.to_string())?;
        self.replace_overview(build(loaded.map)?)
    }

    /// Puts the pyramid in place with its overview at the current size.
    fn replace_overview(&mut self, pyramid: Pyramid) -> Result<(), String> {
        let camera = view::overview_camera(&pyramid, self.params.width, self.params.height)
            .map_err(|e| format!("camera: {e}"))?;
        self.replace(pyramid, camera);
        Ok(())
    }

    /// Puts the pyramid in place, seen by `camera`, on the map's own surface (`render`'s
    /// `--surface auto`).
    fn replace(&mut self, pyramid: Pyramid, camera: Camera) {
        self.options.surface = pyramid.map().surface;
        self.pyramid = pyramid;
        self.params = *camera.params();
        self.forget_frames();
    }

    /// The map's overview ([`view::overview_camera`]: the whole map from above its south edge,
    /// `render`'s default view), `width`×`height` pixels. On error the camera stays as it was.
    pub fn overview(&mut self, width: u32, height: u32) -> Result<(), String> {
        let camera = view::overview_camera(&self.pyramid, width, height)
            .map_err(|e| format!("camera: {e}"))?;
        self.set_camera(camera);
        Ok(())
    }

    /// The paper's camera (Table 1: the map's centre, heading north, FOV 10°, the eye fitted)
    /// at `pitch_deg`, `width`×`height` pixels. On error the camera stays as it was.
    pub fn paper_view(&mut self, pitch_deg: f64, width: u32, height: u32) -> Result<(), String> {
        let camera = view::paper_camera(&self.pyramid, pitch_deg, width, height, self.options)
            .map_err(|e| format!("camera: {e}"))?;
        self.set_camera(camera);
        Ok(())
    }

    /// Moves to `camera`; a new size starts the flicker meters again.
    fn set_camera(&mut self, camera: Camera) {
        let params = *camera.params();
        if (params.width, params.height) != (self.params.width, self.params.height) {
            self.forget_frames();
        }
        self.params = params;
    }

    /// Moves the camera to `params` (the size and the far distance stay), if the core takes
    /// it; otherwise the camera stays as it was.
    pub fn set_view(&mut self, params: CameraParams) -> Result<(), String> {
        let params = CameraParams {
            width: self.params.width,
            height: self.params.height,
            far_m: self.params.far_m,
            ..params
        };
        self.check(params)?;
        self.params = params;
        Ok(())
    }

    /// Flies `metres` along the heading (Sect. 5's flight steps 0.5 m a frame).
    pub fn forward(&mut self, metres: f64) -> Result<(), String> {
        self.set_view(flight::moved(&self.params, 1, metres))
    }

    /// Sets the mode of half `half` from its CLI name (`ps`, `as`, `ss8`, `classic`, …).
    pub fn set_mode(&mut self, half: usize, name: &str) -> Result<(), String> {
        let mode: Mode = name
            .parse()
            .map_err(|e: ParseModeError| format!("--mode: unknown mode {name:?}: {e}"))?;
        let h = self
            .halves
            .get_mut(half)
            .ok_or_else(|| format!("no half {half}"))?;
        if h.mode != mode {
            *h = Half::new(mode);
        }
        Ok(())
    }

    /// Runs `f` on the current frame's tables, the terrain and half `half`.
    fn on_frame<R>(
        &mut self,
        half: usize,
        f: impl FnOnce(&Frame<'_>, &Terrain<'_>, &mut Half) -> Result<R, String>,
    ) -> Result<R, String> {
        let h = self
            .halves
            .get_mut(half)
            .ok_or_else(|| format!("no half {half}"))?;
        with_frame(
            &self.pyramid,
            self.options,
            self.params,
            |frame, terrain| f(frame, terrain, h),
        )
    }

    /// Renders half `half` (no counting: the time is the render's) and updates its flicker
    /// meter.
    pub fn render(&mut self, half: usize) -> Result<(), String> {
        self.on_frame(half, |frame, terrain, h| {
            let rendered =
                render_with(frame, terrain, h.mode, &mut NoCost).map_err(|e| e.to_string())?;
            h.take(&rendered.image);
            Ok(())
        })
    }

    /// Counts half `half`'s frame: every counter, and `V` from the exact visibility pass.
    pub fn count(&mut self, half: usize) -> Result<Counters, String> {
        self.on_frame(half, |frame, terrain, h| {
            let (_, measured) = count(frame, terrain, h.mode).map_err(|e| e.to_string())?;
            h.counters = Counters::new(&measured.total, measured.hidden, measured.missed);
            Ok(h.counters)
        })
    }

    /// Whether the core takes a camera at `params` over this map.
    fn check(&self, params: CameraParams) -> Result<(), String> {
        with_frame(&self.pyramid, self.options, params, |_, _| Ok(()))
    }

    /// A new map or size: the flicker meters start again.
    fn forget_frames(&mut self) {
        for h in &mut self.halves {
            *h = Half::new(h.mode);
        }
    }
}

/// Runs `f` on the frame of a camera at `params` over `pyramid`: the one place the page builds
/// a camera, its terrain and its tables (errors said as the core's, prefixed `camera: `).
fn with_frame<R>(
    pyramid: &Pyramid,
    options: Options,
    params: CameraParams,
    f: impl FnOnce(&Frame<'_>, &Terrain<'_>) -> Result<R, String>,
) -> Result<R, String> {
    let camera = Camera::new(params).map_err(|e| format!("camera: {e}"))?;
    let terrain = pyramid.terrain(options.lod).map_err(|e| e.to_string())?;
    let mut tables = Tables::new(&camera);
    let frame = tables
        .frame(&camera, &terrain, options)
        .map_err(|e| format!("camera: {e}"))?;
    f(&frame, &terrain)
}

/// The pyramid of `map`, with the CLI's default height filter.
fn build(map: Map) -> Result<Pyramid, String> {
    let source = map.source.clone();
    Pyramid::build(map, HeightFilter::default()).map_err(|e| format!("map {source}: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn small() -> App {
        let mut app = App::new().unwrap();
        app.paper_view(20.0, 64, 48).unwrap();
        app
    }

    #[test]
    fn a_still_camera_does_not_flicker_and_a_moving_one_does() {
        let mut app = small();
        app.render(0).unwrap();
        app.render(0).unwrap();
        let h = app.half(0).unwrap();
        assert_eq!((h.mean_dy(), h.changed_6_60()), (0.0, 0));
        assert_eq!(h.rgba().len(), 64 * 48 * 4);
        let still = h.hash();
        app.forward(200.0).unwrap();
        app.render(0).unwrap();
        let h = app.half(0).unwrap();
        assert_ne!(h.hash(), still);
        assert!(h.mean_dy() > 0.0, "{}", h.mean_dy());
    }

    #[test]
    fn the_counters_cover_every_visible_voxel_in_exact_area_sampling() {
        let mut app = small();
        app.set_mode(1, "as-exact").unwrap();
        let c = app.count(1).unwrap();
        assert!(c.v > 0 && c.p > 0);
        assert_eq!((c.m, c.hidden, c.missed), (c.v, 0, 0));
        assert_eq!(c.coverage, 1.0);
    }

    #[test]
    fn a_bad_mode_or_file_changes_nothing_and_says_what_the_cli_says() {
        let mut app = small();
        let e = app.set_mode(0, "ss3").unwrap_err();
        assert!(e.starts_with("--mode: unknown mode \"ss3\""), "{e}");
        assert_eq!(app.half(0).unwrap().mode(), Mode::Ps);

        let before = app.map().source.clone();
        let bad = b"ncols 4\nnrows 3\nxllcorner 0\n";
        let e = app.load_files("bad.asc", bad, None).unwrap_err();
        let dir = std::env::temp_dir().join(format!("footprint-web-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let on_disk = dir.join("bad.asc");
        std::fs::write(&on_disk, bad).unwrap();
        let cli = footprint_maps::load(&on_disk, &LoadOptions::default()).unwrap_err();
        std::fs::remove_dir_all(&dir).unwrap();
        // The same message, but for the name: the page knows the file's name, not its path.
        assert_eq!(
            e,
            cli.to_string()
                .replace(&on_disk.display().to_string(), "bad.asc")
        );
        assert_eq!(app.map().source, before);
    }

    #[test]
    fn a_built_in_terrain_of_a_bad_size_is_refused_and_the_map_stays() {
        let mut app = small();
        let before = app.map().source.clone();
        let e = app.load_builtin(1, 8).unwrap_err();
        assert_eq!(e, "--terrain-size 8: must be 16..=65536");
        assert_eq!(app.map().source, before);
        app.load_builtin(2, 64).unwrap();
        assert_eq!((app.map().width, app.map().height), (64, 64));
    }

    #[test]
    fn a_dropped_grid_becomes_the_map() {
        let mut app = small();
        let mut asc = String::from("ncols 32\nnrows 24\nxllcorner 0\nyllcorner 0\ncellsize 10\n");
        for y in 0..24 {
            let row: Vec<String> = (0..32)
                .map(|x| ((x * 7 + y * 3) % 50).to_string())
                .collect();
            asc.push_str(&row.join(" "));
            asc.push('\n');
        }
        app.load_files("hill.asc", asc.as_bytes(), None).unwrap();
        assert_eq!((app.map().width, app.map().height), (32, 24));
        assert!(
            app.map().source.contains("hill.asc"),
            "{}",
            app.map().source
        );
        app.render(0).unwrap();
        app.render(1).unwrap();
    }

    /// A map the user picks opens in the view `footprint render --dem` takes of it (the
    /// overview: the map itself), not the paper's view of its centre, which on a 300×250 map
    /// is a wallpaper of its mirrored copies.
    #[test]
    fn a_picked_map_opens_in_the_view_render_takes_of_it() {
        let (w, h) = (300u32, 250u32);
        let mut asc = format!("ncols {w}\nnrows {h}\nxllcorner 0\nyllcorner 0\ncellsize 10\n");
        for y in 0..h {
            let row: Vec<String> = (0..w)
                .map(|x| {
                    let (fx, fy) = (f64::from(x) / 23.0, f64::from(y) / 17.0);
                    format!(
                        "{:.0}",
                        200.0 + 60.0 * fx.sin() * fy.cos() + 0.2 * f64::from(y)
                    )
                })
                .collect();
            asc.push_str(&row.join(" "));
            asc.push('\n');
        }
        let mut app = small();
        app.load_files("hill.asc", asc.as_bytes(), None).unwrap();
        let expected = view::overview_camera(&app.pyramid, 64, 48).unwrap();
        assert_eq!(app.params(), expected.params());
        let mirrored = with_frame(&app.pyramid, app.options, app.params, |frame, terrain| {
            Ok(view::coverage(app.map(), frame, terrain))
        })
        .unwrap();
        assert!(mirrored.terrain() > 0);
        assert!(
            mirrored.mirrored_fraction() < 0.05,
            "{:.3} of the terrain mirrored",
            mirrored.mirrored_fraction()
        );
        // The paper's view stays a button away.
        app.paper_view(20.0, 64, 48).unwrap();
        assert_eq!(app.params().fov_deg, view::PAPER_FOV_DEG);
        app.overview(64, 48).unwrap();
        assert_eq!(app.params(), expected.params());
    }

    /// A baked map (`footprint map bake`) loads on the page as on the CLI, and a corrupt one
    /// is one line that leaves the map as it was.
    #[test]
    fn a_baked_map_loads_and_a_corrupt_one_is_refused() {
        let map = procedural(2, 64);
        let pyramid = Pyramid::build(map.clone(), HeightFilter::default()).unwrap();
        let mut bytes = Vec::new();
        // In strips of 16 columns, as `map bake` writes a file by default (of 64).
        footprint_maps::baked::write(&pyramid, "test", Some(4), &mut bytes).unwrap();
        let mut app = App::new().unwrap();
        app.load_files("m.fpmap", &bytes, None).unwrap();
        assert_eq!((app.map().width, app.map().height), (64, 64));
        assert_eq!(app.map().strips, Some(4));
        assert_eq!(app.map().row_major().unwrap().heights, map.heights);
        app.render(0).unwrap();
        let before = app.map().source.clone();
        // The last byte of the coarsest level's colour (the padding after it is no level's).
        let layout = footprint_core::prelude::baked::Layout::in_strips(64, 64, Some(4)).unwrap();
        bytes[layout.pyramid()[1].end - 1] ^= 1;
        let e = app.load_files("m.fpmap", &bytes, None).unwrap_err();
        assert!(e.contains("m.fpmap") && e.contains("checksum"), "{e}");
        assert_eq!(app.map().source, before);
    }
}
