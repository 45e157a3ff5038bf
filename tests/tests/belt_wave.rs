//! Rotating vs non-rotating flowing-material belt (Ribaric §6.2, Fig. 6-3; seed-000 note §2.2,
//! example B0): `flowing::belt::wave`.

use flowing::belt::wave::{WaveConfig, dominant_frequency, wave_run, wave_speed};
use flowing::belt::{BeltMesh, BeltReduction, FlowingSettings};

/// Ribaric Table 6-1 with all free-node modes and 11 mm span elements: the wave packet needs
/// the short wavelengths.
fn config() -> (belt::Drive, FlowingSettings) {
    (
        drives::table_6_1::drive(),
        FlowingSettings {
            mesh: BeltMesh {
                span_element: 0.45 / 40.0,
                ..BeltMesh::default()
            },
            reduction: BeltReduction { free_modes: None },
            ..FlowingSettings::default()
        },
    )
}

/// Least-squares slope of `y` against `t`.
fn slope(t: &[f64], y: &[f64]) -> f64 {
    let n = t.len() as f64;
    let (mt, my) = (t.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = t.iter().zip(y).map(|(a, b)| (a - mt) * (b - my)).sum();
    let sxx: f64 = t.iter().map(|a| (a - mt) * (a - mt)).sum();
    sxy / sxx
}

// Reference: d'Alembert's solution of the (axially moving) string, the span of Table 6-1 with
// c = √(T0/ρA) = 56.8 m/s: an initial bump released with no transverse material velocity splits
// into two equal halves running at v ± c, so before they reach the pulleys the deflection
// centroid moves at the belt speed v (0 at rest) and, at rest, the deflection stays symmetric
// about the span middle.
#[test]
fn wave_splits_at_rest_and_is_advected_when_running() {
    let (cfg, settings) = config();
    let c = wave_speed(&cfg);
    let s = WaveConfig {
        t_end: 2e-3,
        samples: 40,
        step: 1e-5,
        ..Default::default()
    };
    let rest = wave_run(&cfg, &settings, &s, false).unwrap();
    let run = wave_run(&cfg, &settings, &s, true).unwrap();
    let v = s.belt_speed;
    // before the faster front reaches a pulley: half a span minus the bump's half width at v + c
    let span = 0.45;
    let t_free = (0.5 - s.half_width) * span / (v + c);
    let pick = |r: &flowing::belt::wave::WaveRun| -> (Vec<f64>, Vec<f64>) {
        r.times
            .iter()
            .zip(&r.centroid)
            .filter(|(t, _)| **t <= t_free)
            .map(|(t, x)| (*t, *x))
            .unzip()
    };
    let (tr, xr) = pick(&rest);
    let (tm, xm) = pick(&run);
    let (vr, vm) = (slope(&tr, &xr), slope(&tm, &xm));
    println!(
        "c = {c:.2} m/s, v = {v} m/s, {} samples before t = {t_free:.2e} s: centroid speed at rest {vr:+.3} m/s, running {vm:+.3} m/s",
        tr.len()
    );
    assert!(tr.len() >= 5);
    assert!(vr.abs() < 0.05 * v, "centroid drifts at rest: {vr}");
    assert!(
        (vm - v).abs() < 0.2 * v,
        "centroid speed {vm} vs belt speed {v}"
    );
    // at rest, the split is symmetric about the span middle
    let k = tr.len() - 1;
    let w = &rest.span_deflection[k];
    let x = &rest.span_position;
    // the bump was centred on the span middle (positions count from the driven pulley's centre
    // projection, see `WaveRun::span_position`)
    let xm = 0.5 * span;
    let amp = w.iter().map(|a| a.abs()).fold(0.0, f64::max);
    let mut worst = 0.0f64;
    for (i, &xi) in x.iter().enumerate() {
        // mirror point by linear interpolation
        let xr = 2.0 * xm - xi;
        if let Some(j) = x.windows(2).position(|p| p[0] <= xr && xr <= p[1]) {
            let f = (xr - x[j]) / (x[j + 1] - x[j]);
            let wr = w[j] + f * (w[j + 1] - w[j]);
            worst = worst.max((w[i] - wr).abs());
        }
    }
    println!(
        "at rest, t = {:.2e} s: largest asymmetry {worst:.2e} m of peak {amp:.2e} m",
        rest.times[k]
    );
    assert!(worst < 0.1 * amp);
}

// Reference: the natural frequencies of an axially moving string, ω_n = nπ (c² − v²)/(c L)
// (Ribaric §4.2; Wickert & Mote 1990): running at v = c/2, the span's fundamental falls by the
// factor 1 − v²/c² = 0.75 relative to the belt at rest (bending stiffness and the arcs
// perturb it: 8 % tolerance).
#[test]
fn span_frequency_falls_with_belt_speed() {
    let (cfg, settings) = config();
    let c = wave_speed(&cfg);
    let s = WaveConfig {
        half_width: 0.4,
        t_end: 0.12,
        samples: 600,
        step: 1e-4,
        ..Default::default()
    };
    let rest = wave_run(&cfg, &settings, &s, false).unwrap();
    let run = wave_run(&cfg, &settings, &s, true).unwrap();
    let f_string = c / (2.0 * 0.45);
    let f0 = dominant_frequency(&rest.times, &rest.midspan, 0.4 * f_string, 1.6 * f_string);
    let f1 = dominant_frequency(&run.times, &run.midspan, 0.3 * f_string, 1.6 * f_string);
    let v = s.belt_speed;
    let expected = 1.0 - v * v / (c * c);
    println!(
        "span fundamental: string c/2L = {f_string:.2} Hz, at rest {f0:.2} Hz, at {v} m/s {f1:.2} Hz; ratio {:.4} (1 − v²/c² = {expected:.4})",
        f1 / f0
    );
    assert!((f0 - f_string).abs() < 0.15 * f_string);
    assert!((f1 / f0 - expected).abs() < 0.08 * expected);
}
