//! Height-grid CSV reader of the tire's roads (`contact::spatial::HeightGrid::parse_csv`,
//! issue 38): any text gives a grid or a typed error naming a line of the text (0 for the
//! whole file), never a panic or more nodes than the ceiling; a grid has strictly increasing
//! axes, finite heights and slope bounds, and finite interpolated heights and derivatives
//! everywhere (inside, on the nodes and beyond the edges). The same checks run on mutated files
//! in every `cargo test` (`contact::spatial::height_grid` unit tests).
#![no_main]
use contact::spatial::HeightGrid;
use libfuzzer_sys::fuzz_target;

const MAX_POINTS: usize = 10_000;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match HeightGrid::parse_csv(text, MAX_POINTS) {
        Ok(g) => {
            let (x, y) = (g.x(), g.y());
            assert!(x.len() >= 2 && y.len() >= 2);
            assert!(x.len() * y.len() <= MAX_POINTS);
            assert_eq!(g.heights().len(), x.len() * y.len());
            assert!(x.windows(2).all(|w| w[0] < w[1]) && y.windows(2).all(|w| w[0] < w[1]));
            assert!(g.heights().iter().all(|h| h.is_finite()));
            assert!(g.slope_bounds().iter().all(|s| s.is_finite() && *s >= 0.0));
            let (x0, x1, y0, y1) = (x[0], x[x.len() - 1], y[0], y[y.len() - 1]);
            for (a, b) in [
                (x0, y0),
                (x1, y1),
                (0.5 * (x0 + x1), 0.5 * (y0 + y1)),
                (x[x.len() / 2], y[y.len() / 2]),
                (x0 - 1.0, y1 + 1.0),
            ] {
                let h = g.height(a, b);
                assert!(h.h.is_finite() && h.hx.is_finite() && h.hy.is_finite() && h.hxy.is_finite());
            }
        }
        Err(e) => assert!(e.line <= text.split('\n').count(), "{e}"),
    }
});
