//! footprint-firmware's library: what both firmware binaries share.
//!
//! * [`scene`]: the level-0 map and the camera that `build.rs` baked from
//!   `footprint_scenes::firmware::scene()`, and the specular plate from its
//!   `plate()` ([`PlateVertex`], decoded on the chip by [`core_calls::plate_vertex`]);
//! * [`core_calls`]: every call into `footprint-core` that does real work, behind
//!   `#[inline(never)]`, so the core's code can be told apart in the symbol table;
//! * [`clock`]: instruction counts from SysTick under QEMU's `-icount shift=0`;
//! * [`stack`]: the stack's high-water mark, by painting;
//! * [`image_hash`] and [`Ratio`] for the printed lines.
//!
//! The binaries are `src/main.rs` (the full check: three modes, counters, error paths, instruction
//! counts) and `src/bin/minimal.rs` (the smallest embedding: area sampling only, for sizes).

#![no_std]
#![deny(unsafe_code)]

use core::fmt;

use footprint_core::prelude::{frame_buffers, FrameBuffers};
use footprint_core::Rgb;

use footprint_core::prelude::Vertex;
use scene::{FAN_LINES, FAN_ROWS, HEIGHT, PLATE_PIXELS, PLATE_VERTEX_COUNT, PYRAMID_CELLS, WIDTH};

pub mod core_calls;

/// The scene baked by `build.rs`: the level-0 map (in the `.scene` section) and the camera.
// `link_section` counts as unsafe code: the section is memory.x's `.scene`, in flash, read-only.
#[allow(clippy::unreadable_literal, clippy::large_const_arrays, unsafe_code)]
pub mod scene {
    use crate::PlateVertex;
    use footprint_core::prelude::CameraParams;
    #[allow(unused_imports)] // used when the plate's mode is an aggressive clamp
    use footprint_core::prelude::Power;
    use footprint_core::prelude::{Clamp, Method};
    use footprint_core::Rgb;
    include!(concat!(env!("OUT_DIR"), "/scene.rs"));
}

/// Bytes aligned to a page, as a baked map's sections need (its heights are lent as `u16`):
/// `include_bytes!` alone promises an alignment of 1.
#[repr(C, align(4096))]
#[derive(Debug)]
pub struct Aligned<T: ?Sized>(pub T);

/// The glint frame: the firmware's terrain frame lit by a low sun straight ahead
/// (`scene::GLINT_AZIMUTH`, `scene::GLINT_ELEVATION`, baked from
/// `footprint_scenes::firmware::Scene::glint_sun`), the core's `AMBIENT_DIFFUSE`, the paper's
/// AS and Amanatides' aggressive clamp keeping 99 % of the highlight's power.
pub mod glint {
    use footprint_core::prelude::{Clamp, Power, Specular};

    /// The highlight's antialiasing, `clamp99`: `footprint_scenes::firmware::GLINT_SPECULAR`
    /// (an enum the build script does not bake); the bit-exactness test fails if they differ.
    pub const SPECULAR: Specular = Specular::Clamp(Clamp::Aggressive(Power::P99));
}

/// The `as` frame through the embedded-graphics sink (`footprint_core::embedded`): the walk
/// writes the display's `Rgb565` into [`DisplayBuffer`], which is drawn into a [`Checking`]
/// display.
pub mod display {
    use core::convert::Infallible;

    use embedded_graphics_core::draw_target::DrawTarget;
    use embedded_graphics_core::geometry::{OriginDimensions, Size};
    use embedded_graphics_core::pixelcolor::Rgb565;
    use embedded_graphics_core::Pixel;
    use footprint_core::prelude::PixelSink;
    use footprint_core::Rgb;

    use crate::scene::{HEIGHT, WIDTH};

    /// A `WIDTH × HEIGHT` display of `Rgb565` that stores nothing: each pixel drawn is compared
    /// with the pixel of the `Rgb` render it should show, converted as embedded-graphics
    /// converts `Rgb888` ([`PixelSink::from_rgb`]).
    #[derive(Debug)]
    pub struct Checking<'a> {
        expected: &'a [Rgb],
        /// Pixels drawn inside the display.
        pub checked: u32,
        /// Pixels drawn that are not the `Rgb` render's, or outside the display.
        pub differ: u32,
    }

    impl<'a> Checking<'a> {
        /// A display that expects `expected`, row-major from the top.
        pub fn new(expected: &'a [Rgb]) -> Self {
            Self {
                expected,
                checked: 0,
                differ: 0,
            }
        }
    }

    impl OriginDimensions for Checking<'_> {
        fn size(&self) -> Size {
            Size::new(WIDTH as u32, HEIGHT as u32)
        }
    }

    impl DrawTarget for Checking<'_> {
        type Color = Rgb565;
        type Error = Infallible;

        fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Infallible>
        where
            I: IntoIterator<Item = Pixel<Rgb565>>,
        {
            for Pixel(p, color) in pixels {
                let at = usize::try_from(p.y)
                    .ok()
                    .zip(usize::try_from(p.x).ok())
                    .filter(|&(y, x)| x < WIDTH && y < HEIGHT)
                    .and_then(|(y, x)| self.expected.get(y * WIDTH + x));
                match at {
                    Some(&rgb) if Rgb565::from_rgb(rgb) == color => self.checked += 1,
                    _ => self.differ += 1,
                }
            }
            Ok(())
        }
    }
}

/// The display buffer of the embedded-graphics frame ([`display`]), in `.bss`: 2 bytes a pixel.
#[derive(Debug)]
pub struct DisplayBuffer {
    /// The frame in the display's colour, row-major from the top.
    pub pixels: &'static mut [embedded_graphics_core::pixelcolor::Rgb565; WIDTH * HEIGHT],
}

impl DisplayBuffer {
    /// Takes the buffer: `Some` the first time only.
    #[inline(never)]
    pub fn take() -> Option<Self> {
        use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
        Some(Self {
            pixels: cortex_m::singleton!(
                DISPLAY: [Rgb565; WIDTH * HEIGHT] = [Rgb565::BLACK; WIDTH * HEIGHT]
            )?,
        })
    }
}

/// Instruction counts from SysTick.
///
/// QEMU's mps2 boards clock SysTick's processor-clock source at SYSCLK, 25 MHz of *virtual*
/// time. With `-icount shift=0` every instruction advances virtual time by exactly 1 ns, so
/// one tick is 40 instructions: these are instruction counts, not Cortex-M4 cycles (a real M4
/// spends more than one cycle on loads, taken branches and divisions).
/// [`calibrate`](clock::calibrate) checks the conversion on a loop of known length.
pub mod clock {
    use core::sync::atomic::{AtomicU32, Ordering};

    use cortex_m::peripheral::syst::SystClkSource;
    use cortex_m::peripheral::SYST;

    /// QEMU's mps2 SYSCLK, which drives SysTick's processor-clock source.
    pub const SYSCLK_HZ: u64 = 25_000_000;

    /// Virtual nanoseconds (= instructions, under `-icount shift=0`) per SysTick tick.
    pub const INSTRUCTIONS_PER_TICK: u64 = 1_000_000_000 / SYSCLK_HZ;

    /// SysTick's reload value: the full 24 bits.
    const RELOAD: u32 = 0x00ff_ffff;

    /// SysTick wraps (one per 2^24 ticks, 671 million instructions).
    static WRAPS: AtomicU32 = AtomicU32::new(0);

    /// Starts SysTick from the processor clock, wrapping every 2^24 ticks with an exception;
    /// the binary's `SysTick` handler must call [`on_wrap`].
    pub fn start(syst: &mut SYST) {
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(RELOAD);
        syst.clear_current();
        syst.enable_interrupt();
        syst.enable_counter();
    }

    /// Counts one wrap: call it from the `SysTick` exception handler.
    pub fn on_wrap() {
        WRAPS.fetch_add(1, Ordering::Relaxed);
    }

    /// SysTick ticks since it first loaded its reload value, wraps included.
    ///
    /// The counter runs `RELOAD, …, 1, 0, RELOAD, …`; the exception fires as it reaches 0, and
    /// it reads 0 before its first load too. A 0 is therefore ambiguous; it lasts one tick, so
    /// read again.
    pub fn ticks() -> u64 {
        loop {
            let wraps = WRAPS.load(Ordering::SeqCst);
            let current = SYST::get_current();
            // A wrap between the two reads raises the exception at once, so they would differ.
            if current != 0 && WRAPS.load(Ordering::SeqCst) == wraps {
                return u64::from(wraps) * (u64::from(RELOAD) + 1) + u64::from(RELOAD - current);
            }
        }
    }

    /// The instructions `f` took (to within one tick), and its result.
    pub fn instructions<T>(f: impl FnOnce() -> T) -> (u64, T) {
        let t0 = ticks();
        let r = f();
        let t1 = ticks();
        ((t1 - t0) * INSTRUCTIONS_PER_TICK, r)
    }

    /// Times a loop of known length, `cortex_m::asm::delay(n)`: `n + 1` iterations of
    /// `subs; bne`. Returns `(expected, measured)` instructions; they agree to within 0.1 %
    /// only if one tick is [`INSTRUCTIONS_PER_TICK`] instructions.
    pub fn calibrate() -> (u64, u64) {
        const N: u32 = 2_000_000;
        let (measured, ()) = instructions(|| cortex_m::asm::delay(N));
        (2 * (u64::from(N) + 1), measured)
    }
}

/// The stack's high-water mark: paint a window below the stack pointer, run, and find the
/// lowest word that changed.
pub mod stack {
    use core::sync::atomic::{AtomicUsize, Ordering};

    /// The pattern painted.
    const PAINT: u32 = 0xa5a5_a5a5;
    /// Bytes below the stack pointer that are painted (RAM is 4 MiB; the statics are below).
    pub const WINDOW: usize = 256 * 1024;
    /// Bytes just below the stack pointer left alone (exception frames, this function's own).
    const GAP: usize = 256;

    /// The painted window, `BOTTOM..END`.
    static BOTTOM: AtomicUsize = AtomicUsize::new(0);
    static END: AtomicUsize = AtomicUsize::new(0);

    extern "C" {
        /// The initial stack pointer, the top of RAM (cortex-m-rt's `link.x`).
        static _stack_start: u32;
    }

    /// Paints the window. Call it early in `main`, before the work to be measured.
    pub fn paint() {
        let sp = cortex_m::register::msp::read() as usize;
        let (bottom, end) = (sp - WINDOW, sp - GAP);
        for addr in (bottom..end).step_by(4) {
            // SAFETY: the window lies in RAM between the statics and the stack pointer: free,
            // aligned, and not used by anything until the stack grows into it.
            #[allow(unsafe_code)]
            unsafe {
                core::ptr::write_volatile(addr as *mut u32, PAINT)
            };
        }
        BOTTOM.store(bottom, Ordering::SeqCst);
        END.store(end, Ordering::SeqCst);
    }

    /// The most stack used since [`paint`], in bytes from the top of RAM; `None` if nothing
    /// was painted or the whole window was used.
    pub fn used() -> Option<usize> {
        // Only the symbol's address is taken, which is safe; it is never read.
        let top = core::ptr::addr_of!(_stack_start) as usize;
        let (bottom, end) = (BOTTOM.load(Ordering::SeqCst), END.load(Ordering::SeqCst));
        let lowest = (bottom..end)
            .step_by(4)
            .find(|&addr| {
                // SAFETY: the painted window, as in `paint`; reads only.
                #[allow(unsafe_code)]
                let word = unsafe { core::ptr::read_volatile(addr as *const u32) };
                word != PAINT
            })
            .unwrap_or(end);
        (bottom < end && lowest > bottom).then(|| top - lowest)
    }
}

/// Every buffer the core borrows, in `.bss`: the firmware's whole RAM apart from the stack.
#[derive(Debug)]
pub struct Buffers {
    /// Heights of pyramid levels 1 and up, built on the chip: three grids per level (for rays
    /// along x and along y, and the conservative maximum for skipping empty air).
    pub pyramid_heights: &'static mut [u16; 3 * PYRAMID_CELLS],
    /// Colours of pyramid levels 1 and up.
    pub pyramid_colors: &'static mut [Rgb; PYRAMID_CELLS],
    /// The frame's tables (the paper's projection, `W × H`: `H + 1` row slopes, `W` columns).
    pub frame: &'static mut frame_buffers!(WIDTH, HEIGHT),
    /// The image, row-major from the top.
    pub image: &'static mut [Rgb; WIDTH * HEIGHT],
}

/// The rolled and the level frame's buffers (the exact projection's fans, up to
/// `FAN_LINES × FAN_ROWS`, with the walk's scratch grid), in `.bss`.
pub type FanBuffers = &'static mut frame_buffers!(exact FAN_LINES, FAN_ROWS);

/// Takes the fans' buffers: `Some` the first time only.
#[inline(never)]
pub fn take_fan_buffers() -> Option<FanBuffers> {
    cortex_m::singleton!(FAN: frame_buffers!(exact FAN_LINES, FAN_ROWS) = FrameBuffers::new())
}

impl Buffers {
    /// Takes the buffers: `Some` the first time only. (`cortex_m::singleton!` builds each
    /// initial value on the stack before it moves it into its static, so this function's
    /// frame is large for a moment; it returns before any rendering.)
    #[inline(never)]
    pub fn take() -> Option<Self> {
        Some(Self {
            pyramid_heights: cortex_m::singleton!(
                PYRAMID_HEIGHTS: [u16; 3 * PYRAMID_CELLS] = [0; 3 * PYRAMID_CELLS]
            )?,
            pyramid_colors: cortex_m::singleton!(
                PYRAMID_COLORS: [Rgb; PYRAMID_CELLS] = [Rgb::new(0, 0, 0); PYRAMID_CELLS]
            )?,
            frame: cortex_m::singleton!(FRAME: frame_buffers!(WIDTH, HEIGHT) = FrameBuffers::new())?,
            image: cortex_m::singleton!(
                IMAGE: [Rgb; WIDTH * HEIGHT] = [Rgb::new(0, 0, 0); WIDTH * HEIGHT]
            )?,
        })
    }
}

/// One vertex of the specular plate as `build.rs` bakes it (the host's
/// `footprint_scenes::firmware::PlateVertex`): position and depth in the fixed-point
/// form of the core's [`Vertex`], the normal as the host's `f64` direction (bit patterns).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlateVertex {
    /// `x`, pixels × 256.
    pub x_q8: i32,
    /// `y`, pixels × 256 (down).
    pub y_q8: i32,
    /// Depth, 0 nearest.
    pub z: u16,
    /// The normal direction, `f64::to_bits` of each component.
    pub normal: [u64; 3],
}

/// The specular plate's buffers, in `.bss`; only `src/main.rs` takes them.
#[derive(Debug)]
pub struct PlateBuffers {
    /// The plate's vertices in the core's form, decoded on the chip from `PLATE_VERTICES`;
    /// empty when taken.
    pub vertices: &'static mut heapless::Vec<Vertex, PLATE_VERTEX_COUNT>,
    /// The colour buffer.
    pub color: &'static mut [Rgb; PLATE_PIXELS],
    /// The depth buffer.
    pub depth: &'static mut [u16; PLATE_PIXELS],
    /// Per pixel: detection flagged the last fragment drawn there.
    pub flagged: &'static mut [bool; PLATE_PIXELS],
}

impl PlateBuffers {
    /// Takes the buffers: `Some` the first time only.
    #[inline(never)]
    pub fn take() -> Option<Self> {
        Some(Self {
            vertices: cortex_m::singleton!(
                PLATE_VERTICES: heapless::Vec<Vertex, PLATE_VERTEX_COUNT> = heapless::Vec::new()
            )?,
            color: cortex_m::singleton!(
                PLATE_COLOR: [Rgb; PLATE_PIXELS] = [Rgb::new(0, 0, 0); PLATE_PIXELS]
            )?,
            depth: cortex_m::singleton!(PLATE_DEPTH: [u16; PLATE_PIXELS] = [0; PLATE_PIXELS])?,
            flagged: cortex_m::singleton!(
                PLATE_FLAGGED: [bool; PLATE_PIXELS] = [false; PLATE_PIXELS]
            )?,
        })
    }
}

/// The 64-bit FNV-1a hash of an image's bytes, `r, g, b` per pixel, row-major from the top
/// (the host's `footprint_host::experiment::firmware::image_hash`).
pub fn image_hash(image: &[Rgb]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for c in image {
        for b in [c.r, c.g, c.b] {
            h = (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    h
}

/// `num / den` rounded half up to `places` decimals, for `#` lines.
#[derive(Debug)]
pub struct Ratio {
    /// Numerator.
    pub num: u64,
    /// Denominator.
    pub den: u64,
    /// Decimals printed.
    pub places: u32,
}

impl Ratio {
    /// `num / den` to one decimal.
    pub fn tenths(num: u64, den: u64) -> Self {
        Self {
            num,
            den,
            places: 1,
        }
    }
}

impl fmt::Display for Ratio {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let unit = 10u64.pow(self.places);
        let scaled = (self.num * unit + self.den / 2) / self.den.max(1);
        write!(
            f,
            "{}.{:0width$}",
            scaled / unit,
            scaled % unit,
            width = self.places as usize
        )
    }
}
