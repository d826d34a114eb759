//! `sdfc render --frames START..END --fps N`: an animation of the scene's `time`, the module
//! compiled and prepared once and only its `Params` uniform changed between frames, written as
//! an animated GIF or a numbered PNG sequence.

use super::{Job, progress_bar};
use crate::cli::{Error, RenderArgs, messages::done, write_file};
use sdfc::images::{self, Channel};
use sdfc_compiler::check::TIME;
use sdfc_compiler::scene::ParamDecl;
use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// Most frames one command renders.
const MAX_FRAMES: u32 = 10_000;

/// Where the frames go.
pub enum Sink {
    /// One animated GIF (looping), frames `1/fps` s apart.
    Gif(PathBuf),
    /// One PNG per frame: the path's run of `#` replaced by the frame's number, zero-padded
    /// to the run's length (`out_###.png`: `out_000.png`, `out_001.png`, …).
    Pngs(String),
}

/// `--frames START..END` (END excluded) as the frame numbers.
pub fn parse_frames(text: &str) -> Result<std::ops::Range<u32>, Error> {
    let bad = || {
        format!(
            "error: `--frames {text}` is not START..END (whole frame numbers, END excluded), e.g. `--frames 0..60`"
        )
    };
    let (a, b) = text.split_once("..").ok_or_else(bad)?;
    let (a, b): (u32, u32) = (
        a.trim().parse().map_err(|_| bad())?,
        b.trim().parse().map_err(|_| bad())?,
    );
    if b <= a {
        return Err(
            format!("error: `--frames {text}` has no frame: END must be above START").into(),
        );
    }
    if b - a > MAX_FRAMES {
        return Err(format!(
            "error: `--frames {text}` is {} frames; at most {MAX_FRAMES} in one command",
            b - a
        )
        .into());
    }
    Ok(a..b)
}

/// Where `--frames` writes, from the output path: `.gif`, or `.png` with a run of `#`.
pub fn sink(output: &Path) -> Result<Sink, Error> {
    let text = output.to_string_lossy().to_string();
    let ext = output
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match ext.as_deref() {
        Some("gif") => Ok(Sink::Gif(output.to_path_buf())),
        Some("png") if text.contains('#') => Ok(Sink::Pngs(text)),
        _ => Err(format!(
            "error: `{text}`: `--frames` writes an animated GIF (`-o anim.gif`) or numbered PNGs (`-o frames/out_###.png`, `#`s becoming the frame's number)"
        )
        .into()),
    }
}

impl Sink {
    /// The file of frame `k` (a PNG sequence).
    fn numbered(pattern: &str, k: u32) -> PathBuf {
        let start = pattern.find('#').expect("a # run");
        let len = pattern[start..].chars().take_while(|&c| c == '#').count();
        let name = format!(
            "{}{:0len$}{}",
            &pattern[..start],
            k,
            &pattern[start + len..]
        );
        PathBuf::from(name)
    }
}

/// The `Params` bytes of each frame: `time` = `start` + k/`fps` for frame k, every other
/// parameter as given (its default or `--param`); an error if a frame's `time` leaves the
/// range `time` was declared with (λ and bounds hold only there).
pub fn settings(
    params: &[ParamDecl],
    frames: std::ops::Range<u32>,
    fps: f64,
    start: f64,
) -> Result<Vec<Vec<u8>>, Error> {
    frames
        .map(|k| {
            let mut p = params.to_vec();
            for d in &mut p {
                if d.name == TIME {
                    let t = start + f64::from(k) / fps;
                    if let Some((lo, hi)) = d.range
                        && !(lo.x..=hi.x).contains(&t)
                    {
                        return Err(format!(
                            "error: frame {k} is at time {t} s, outside the range {}..{} the scene declares for `time`",
                            lo.x, hi.x
                        )
                        .into());
                    }
                    d.value.x = t;
                }
            }
            Ok(sdfc_compiler::lower::params::bytes(&p))
        })
        .collect()
}

/// Frames whose `time` the annotations are checked at: at most this many, evenly spread.
const CHECKED_FRAMES: u32 = 16;

/// The annotations checked at the `time` of frames spread over the animation, first and last
/// included (as `render --time` checks its one value; nothing is done where no annotated shape
/// reads `time`): each one too small at some frame is said once, with the first such frame.
fn verify_frames(
    scene: &sdfc_compiler::scene::Scene,
    frames: std::ops::Range<u32>,
    fps: f64,
    start: f64,
) {
    let n = frames.len() as u32;
    if n == 0 {
        return;
    }
    let picks = n.min(CHECKED_FRAMES);
    let mut said: Vec<sdfc_compiler::diag::Span> = Vec::new();
    for i in 0..picks {
        let k = frames.start
            + if picks == 1 {
                0
            } else {
                i * (n - 1) / (picks - 1)
            };
        let t = start + f64::from(k) / fps;
        let values = std::collections::HashMap::from([(TIME.to_string(), vec![t])]);
        for d in sdfc_compiler::lipschitz::too_small_at(scene, &values) {
            if !said.contains(&d.span) {
                say!(
                    "warning: at frame {k} (time = {t} s), {}: {}",
                    d.message,
                    d.label
                );
                said.push(d.span);
            }
        }
    }
}

/// Collects the frames as they are finished and writes them.
pub struct Writer {
    sink: Sink,
    first: u32,
    fps: f64,
    size: (u32, u32),
    gif: Option<(image::codecs::gif::GifEncoder<Shared>, Shared)>,
    written: u32,
}

/// The GIF's bytes in memory (the file is written whole at the end), shared with its encoder,
/// which writes the trailer when it is dropped.
#[derive(Clone, Default)]
struct Shared(Rc<RefCell<Vec<u8>>>);

impl std::io::Write for Shared {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.0.borrow_mut().extend_from_slice(buf);
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

impl Writer {
    /// A writer of `size` frames numbered from `first`.
    pub fn new(sink: Sink, first: u32, fps: f64, size: (u32, u32)) -> Result<Writer, Error> {
        let gif = match &sink {
            Sink::Gif(_) => {
                let bytes = Shared::default();
                let mut e = image::codecs::gif::GifEncoder::new_with_speed(bytes.clone(), 10);
                e.set_repeat(image::codecs::gif::Repeat::Infinite)
                    .map_err(|e| Error::Usage(format!("error: cannot start the GIF: {e}")))?;
                Some((e, bytes))
            }
            Sink::Pngs(_) => None,
        };
        Ok(Writer {
            sink,
            first,
            fps,
            size,
            gif,
            written: 0,
        })
    }

    /// Adds the next frame (sRGB RGBA8).
    pub fn add(&mut self, rgba: Vec<u8>) -> Result<(), Error> {
        let (w, h) = self.size;
        let k = self.first + self.written;
        self.written += 1;
        match (&self.sink, &mut self.gif) {
            (Sink::Gif(_), Some((e, _))) => {
                let img = image::RgbaImage::from_raw(w, h, rgba).expect("a whole frame");
                let delay =
                    image::Delay::from_numer_denom_ms(1000, self.fps.round().max(1.0) as u32);
                e.encode_frame(image::Frame::from_parts(img, 0, 0, delay))
                    .map_err(|e| Error::Usage(format!("error: cannot encode frame {k}: {e}")))
            }
            (Sink::Pngs(pattern), _) => {
                let path = Sink::numbered(pattern, k);
                let bytes = images::png(rgba, w, h)?;
                write_file(&path, &bytes)
            }
            _ => unreachable!("a GIF has its encoder"),
        }
    }

    /// Finishes the animation; what was written, for the success line.
    pub fn finish(self) -> Result<String, Error> {
        match (self.sink, self.gif) {
            (Sink::Gif(path), Some((e, bytes))) => {
                drop(e);
                let bytes = bytes.0.borrow().clone();
                write_file(&path, &bytes)?;
                Ok(path.display().to_string())
            }
            (Sink::Pngs(pattern), _) => Ok(format!(
                "{} … {}",
                Sink::numbered(&pattern, self.first).display(),
                Sink::numbered(&pattern, self.first + self.written.saturating_sub(1)).display()
            )),
            _ => unreachable!("a GIF has its encoder"),
        }
    }
}

/// Renders frames `range` of the animation (each with all its samples), writes them to
/// `sink` and says so.
pub fn render(
    args: &RenderArgs,
    job: &Job,
    range: std::ops::Range<u32>,
    sink: Sink,
) -> Result<(), Error> {
    let (w, h) = (job.view.width, job.view.height);
    let first = range.start;
    let fps = f64::from(args.fps);
    let start = args.time.unwrap_or(0.0);
    verify_frames(&job.valued, range.clone(), fps, start);
    let settings = settings(&job.valued.params, range, fps, start)?;
    let count = settings.len();
    let mut writer = Writer::new(sink, first, fps, (w, h))?;
    let mut sum = images::Accumulator::new((w * h) as usize, true);
    let mut taken = 0;
    let bar = progress_bar("rendering tiles");
    job.gpu.render_sequence(
        &job.module,
        (&job.view, job.plan.as_deref()),
        &job.points,
        &settings,
        |done, total| {
            if let Some(b) = &bar {
                b.set_length(total as u64);
                b.set_position(done as u64);
            }
        },
        |_, frame| {
            sum.add(&images::rgba(&frame, Channel::Color, job.scene.trace.steps));
            taken += 1;
            if taken == job.points.len() {
                let done =
                    std::mem::replace(&mut sum, images::Accumulator::new((w * h) as usize, true));
                taken = 0;
                writer.add(done.finish())?;
            }
            Ok(())
        },
    )?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let place = writer.finish()?;
    let still = if job.scene.params.iter().any(|p| p.name == TIME) {
        ""
    } else {
        " (the scene does not read `time`: every frame is the same)"
    };
    let samples = job.samples;
    done(&format!(
        "wrote {place} — {count} frames of {w}×{h} at {} fps, {samples} {} per pixel, {:.1} s, {} ({}){still}",
        args.fps,
        if samples == 1 { "sample" } else { "samples" },
        job.started.elapsed().as_secs_f64(),
        job.gpu.info.name,
        job.gpu.backend()
    ));
    Ok(())
}
