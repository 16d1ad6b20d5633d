//! The embedded-graphics sink (`footprint_core::embedded`, feature `embedded-graphics`): a frame
//! of either projection drawn into a `DrawTarget` of `Rgb565` or `Rgb888` is the `Rgb` render,
//! pixel for pixel, converted by embedded-graphics' own `Rgb888 → Rgb565`, in every mode.

use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use footprint_core::embedded::{self, RenderError};
use footprint_core::prelude::*;
use footprint_host::experiment::paper::paper_camera;
use footprint_host::map::procedural;
use footprint_host::parallel::{render_with, Tables, SS_RATES};
use footprint_host::pyramid::Pyramid;
use footprint_host::view_args::Size as ImageSize;

/// A display of any size: a framebuffer of `C` the test can read back.
struct Screen<C> {
    size: Size,
    pixels: Vec<C>,
}

impl<C: PixelColor + Default> Screen<C> {
    fn new(width: u32, height: u32) -> Self {
        Self {
            size: Size::new(width, height),
            pixels: vec![C::default(); (width * height) as usize],
        }
    }
}

impl<C: PixelColor> OriginDimensions for Screen<C> {
    fn size(&self) -> Size {
        self.size
    }
}

impl<C: PixelColor> DrawTarget for Screen<C> {
    type Color = C;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in pixels {
            if p.x >= 0
                && p.y >= 0
                && (p.x as u32) < self.size.width
                && (p.y as u32) < self.size.height
            {
                self.pixels[p.y as usize * self.size.width as usize + p.x as usize] = c;
            }
        }
        Ok(())
    }
}

fn all_modes() -> Vec<Mode> {
    let mut modes = vec![Mode::Ps, Mode::Li, Mode::As, Mode::AsExact, Mode::Classic];
    modes.extend(SS_RATES.map(Mode::Ss));
    modes
}

#[test]
fn the_embedded_graphics_sink_equals_the_rgb_render_in_both_projections() {
    let map = procedural(5, 256);
    let pyramid = Pyramid::build(map.clone(), HeightFilter::default()).unwrap();
    let terrain = pyramid.terrain(true).unwrap();
    let (w, h) = (48u32, 40u32);
    let size = ImageSize {
        width: w,
        height: h,
    };
    let exact = Options {
        projection: Projection::Exact,
        ..Options::default()
    };
    for pitch in [40.0, 5.0] {
        let camera = paper_camera(&map, &pyramid, pitch, size, true).unwrap();
        for options in [Options::default(), exact] {
            let mut tables = Tables::new(&camera);
            let frame = tables.frame(&camera, &terrain, options).unwrap();
            let projection = options.projection;
            let mut scratch = vec![Rgb::default(); frame.scratch_len()];
            assert_eq!(
                scratch.is_empty(),
                projection == Projection::Paper,
                "only the exact projection walks a scratch grid"
            );
            for mode in all_modes() {
                let rgb = render_with(&frame, &terrain, mode, &mut NoCost)
                    .unwrap()
                    .image;
                // Into embedded-graphics' MockDisplay, in Rgb565.
                let mut mock = MockDisplay::<Rgb565>::new();
                let mut buffer = vec![Rgb565::BLACK; (w * h) as usize];
                embedded::render(
                    &mut mock,
                    &frame,
                    &terrain,
                    &mode,
                    &mut NoCost,
                    &mut scratch,
                    &mut buffer,
                )
                .unwrap();
                // Into a framebuffer, in Rgb888.
                let mut screen = Screen::<Rgb888>::new(w, h);
                let mut buffer888 = vec![Rgb888::BLACK; (w * h) as usize];
                embedded::render(
                    &mut screen,
                    &frame,
                    &terrain,
                    &mode,
                    &mut NoCost,
                    &mut scratch,
                    &mut buffer888,
                )
                .unwrap();
                for y in 0..h {
                    for x in 0..w {
                        let c = rgb[(y * w + x) as usize];
                        let p = Point::new(x as i32, y as i32);
                        let want888 = Rgb888::new(c.r, c.g, c.b);
                        assert_eq!(
                            mock.get_pixel(p),
                            Some(Rgb565::from(want888)),
                            "{mode} {projection:?} pitch {pitch}: Rgb565 pixel ({x}, {y})"
                        );
                        assert_eq!(
                            screen.pixels[(y * w + x) as usize],
                            want888,
                            "{mode} {projection:?} pitch {pitch}: Rgb888 pixel ({x}, {y})"
                        );
                    }
                }
            }
            // `draw` draws an image rendered any other way.
            let rgb = render_with(&frame, &terrain, Mode::As, &mut NoCost)
                .unwrap()
                .image;
            let mut screen = Screen::<Rgb888>::new(w, h);
            embedded::draw(&mut screen, &rgb, w).unwrap();
            let want: Vec<Rgb888> = rgb.iter().map(|c| Rgb888::new(c.r, c.g, c.b)).collect();
            assert_eq!(screen.pixels, want, "pitch {pitch}: the frame drawn");
            // A short scratch is refused with the core's error, not drawn.
            if projection == Projection::Exact {
                let mut buffer = vec![Rgb888::BLACK; (w * h) as usize];
                let refused = embedded::render(
                    &mut screen,
                    &frame,
                    &terrain,
                    &Mode::As,
                    &mut NoCost,
                    &mut scratch[1..],
                    &mut buffer,
                );
                assert!(
                    matches!(
                        refused,
                        Err(RenderError::Core(Error::SliceLength {
                            what: "scratch",
                            ..
                        }))
                    ),
                    "{refused:?}"
                );
            }
        }
    }
}
