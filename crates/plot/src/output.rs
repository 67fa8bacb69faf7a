//! Rendering a figure on both backends and writing the files atomically.

use std::ffi::OsString;
use std::fs;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};

use crate::PlotError;

/// Result of drawing: plotters' errors are turned into their message.
pub(crate) type DrawResult = Result<(), String>;

/// Converts any displayable drawing error into the message kept by [`DrawResult`].
pub(crate) fn msg<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

/// A figure that can draw itself on any plotters backend.
pub(crate) trait Figure {
    /// Image size in pixels (also the SVG's size).
    fn size(&self) -> (u32, u32);
    /// Draws on `root`, which is already filled white.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult;
}

/// `<stem>.<ext>`, appending rather than replacing any dot in the stem's file name.
pub(crate) fn file_path(stem: &Path, ext: &str) -> PathBuf {
    let mut name = OsString::from(stem.as_os_str());
    name.push(".");
    name.push(ext);
    PathBuf::from(name)
}

/// Registers DejaVu Sans (regular and bold) as plotters' `sans-serif` family, once.
fn fonts_ready() -> bool {
    static READY: OnceLock<bool> = OnceLock::new();
    *READY.get_or_init(|| {
        register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular()).is_ok()
            && register_font("sans-serif", FontStyle::Bold, dejavu::sans::bold()).is_ok()
    })
}

/// Draws `fig` as PNG and SVG next to `stem`; returns `[png, svg]`.
pub(crate) fn write_figure<F: Figure>(fig: &F, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    let png_path = file_path(stem, "png");
    let svg_path = file_path(stem, "svg");
    if stem.file_name().is_none() {
        return Err(PlotError::Invalid {
            path: stem.to_path_buf(),
            message: "the stem has no file name".into(),
        });
    }
    if !fonts_ready() {
        return Err(PlotError::Font { path: png_path });
    }
    if let Some(dir) = png_path.parent().filter(|d| !d.as_os_str().is_empty()) {
        fs::create_dir_all(dir).map_err(|source| PlotError::Io {
            path: dir.to_path_buf(),
            source,
        })?;
    }
    let (w, h) = fig.size();

    let png = render_png(fig, w, h).map_err(|message| PlotError::Draw {
        path: png_path.clone(),
        message,
    })?;
    let png = encode_png(&png, w, h).map_err(|message| PlotError::Encode {
        path: png_path.clone(),
        message,
    })?;
    write_atomic(&png_path, &png)?;

    let svg = render_svg(fig, w, h).map_err(|message| PlotError::Draw {
        path: svg_path.clone(),
        message,
    })?;
    write_atomic(&svg_path, svg.as_bytes())?;
    Ok(vec![png_path, svg_path])
}

/// Renders into an RGB8 buffer.
fn render_png<F: Figure>(fig: &F, w: u32, h: u32) -> Result<Vec<u8>, String> {
    let mut rgb = vec![255u8; w as usize * h as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(msg)?;
        fig.draw(&root)?;
        root.present().map_err(msg)?;
    }
    Ok(rgb)
}

/// Renders into an SVG document.
fn render_svg<F: Figure>(fig: &F, w: u32, h: u32) -> Result<String, String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(msg)?;
        fig.draw(&root)?;
        root.present().map_err(msg)?;
    }
    Ok(svg)
}

/// Encodes an RGB8 buffer as PNG.
fn encode_png(rgb: &[u8], w: u32, h: u32) -> Result<Vec<u8>, String> {
    let mut out = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut out, w, h);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().map_err(msg)?;
        writer.write_image_data(rgb).map_err(msg)?;
        writer.finish().map_err(msg)?;
    }
    Ok(out)
}

/// Writes `bytes` through the project's one checked output path
/// (`platoonsim_bounded::output::write_atomic`: tmp + fsync + rename, only over a regular file
/// or a new path, a link followed to its target).
fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), PlotError> {
    platoonsim_bounded::output::write_atomic(path, bytes).map_err(|source| PlotError::Io {
        path: path.to_path_buf(),
        source,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn file_path_appends_the_extension() {
        assert_eq!(
            file_path(Path::new("out/fig_0.5"), "png"),
            PathBuf::from("out/fig_0.5.png")
        );
        assert_eq!(
            file_path(Path::new("a.png"), "tmp"),
            PathBuf::from("a.png.tmp")
        );
    }

    #[test]
    fn the_embedded_font_registers() {
        assert!(fonts_ready());
    }
}
