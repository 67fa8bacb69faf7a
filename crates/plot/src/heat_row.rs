//! Speed contours side by side, each with its own colour bar: maps on different scales
//! in one figure (e.g. simulated | field speeds | their difference).

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::heat::{colour_bar, Figure, BAR_AREA};
use crate::line::title_band;
use crate::output::{self, DrawResult};
use crate::theme;
use crate::Heatmap;

/// Validated maps, one panel each, under a common title.
pub(crate) struct Row<'a> {
    figures: Vec<Figure<'a>>,
    title: &'a str,
}

impl<'a> Row<'a> {
    /// Checks every map (an error names the panel).
    pub fn new(maps: &'a [Heatmap], title: &'a str) -> Result<Self, String> {
        let figures = maps
            .iter()
            .enumerate()
            .map(|(i, h)| Figure::new(h).map_err(|e| format!("panel {}: {e}", i + 1)))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Row { figures, title })
    }
}

impl output::Figure for Row<'_> {
    fn size(&self) -> (u32, u32) {
        let n = self.figures.len().max(1) as u32;
        (n * (520 + BAR_AREA), 600)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult {
        let body = title_band(root, self.title, 56)?;
        let areas = body.split_evenly((1, self.figures.len().max(1)));
        for (f, area) in self.figures.iter().zip(&areas) {
            let (w, _) = area.dim_in_pixel();
            let (cells, bar) = area.split_horizontally(w.saturating_sub(BAR_AREA));
            f.cells(&cells, &theme::PANEL, true)?;
            let missing = f.map().z.iter().flatten().any(|z| !z.is_finite());
            colour_bar(&bar, f.z_range(), &f.map().z_label, missing)?;
        }
        Ok(())
    }
}
