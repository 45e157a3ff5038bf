//! Layouts shared by the layout tests (flowing `layout.rs`, nodal `layout_nodal.rs`, ANCF
//! `ancf_layout.rs`); each test file uses some of them.
#![allow(dead_code)]

use belt::{Layout, Motion, Pulley, Section, Shape, Signal, Tensioner, WrapSide};
use flowing::belt::{BeltMesh, BeltReduction, FlowingBelt, FlowingSettings, NodalBelt};

/// A signal ramped smoothly from 0 to `value` over 0.1 s.
pub fn ramp(value: f64) -> Signal {
    Signal::schedule(vec![(0.0, 0.0), (0.1, value)])
}

/// Crank (ramped to 80 rad/s in 0.1 s), alternator and water pump (each loaded with `load`
/// \[N m\], ramped in 0.1 s), back-side idler on a tensioner arm; installed at 310 N.
pub fn four_pulleys(load: f64) -> Layout {
    let loaded = |j: f64| Motion::load(j, ramp(load));
    let mut layout = Layout::new(
        vec![
            Pulley::new(
                "crank",
                [0.0, 0.0],
                0.075,
                WrapSide::Inside,
                Motion::speed(ramp(80.0)),
            ),
            Pulley::new(
                "alternator",
                [0.12, 0.28],
                0.03,
                WrapSide::Inside,
                loaded(0.003),
            ),
            Pulley::new(
                "tensioner",
                [0.16, 0.10],
                0.035,
                WrapSide::Outside,
                Motion::idler(1e-4),
            ),
            Pulley::new(
                "water pump",
                [0.25, -0.05],
                0.05,
                WrapSide::Inside,
                loaded(0.002),
            ),
        ],
        Section::default(),
        310.0,
    );
    layout.tensioner = Some(Tensioner {
        pulley: 2,
        pivot: [0.13, 0.174],
        stiffness: 30.0,
        preload: -28.0,
        preload_angle: -1.186,
        damping: 0.5,
        dry_friction: 0.0,
        friction_rate: 0.01,
        inertia: 2e-3,
        travel: [-1.6, -0.8],
    });
    // Ribaric's κ = 40 s/m, the law these tests were measured with (stated, whatever the default)
    layout.contact = belt::BeltContact::ribaric();
    layout
}

/// The flowing settings of [`four_pulleys`]: 40 mm span and 12 mm wrap elements, 12 modes.
pub fn four_pulleys_settings() -> FlowingSettings {
    FlowingSettings {
        mesh: BeltMesh {
            span_element: 0.04,
            arc_element: 0.012,
            contact_margin_nodes: 1,
        },
        reduction: BeltReduction {
            free_modes: Some(12),
        },
        ..FlowingSettings::default()
    }
}

/// Driver (R 50 mm) and driven (R 50 mm, J of Table 6-1) 0.3 m apart, an idler (R 30 mm)
/// below them closing a triangle; the Table 6-1 belt, contact and damping at 310 N.
pub fn triangle() -> Layout {
    Layout {
        contact: belt::BeltContact::ribaric(),
        ..Layout::new(
            vec![
                Pulley::new(
                    "driver",
                    [0.0, 0.0],
                    0.05,
                    WrapSide::Inside,
                    Motion::speed(Signal::constant(0.0)),
                ),
                Pulley::new(
                    "driven",
                    [0.3, 0.0],
                    0.05,
                    WrapSide::Inside,
                    Motion::load(0.013, Signal::constant(0.0)),
                ),
                Pulley::new(
                    "idler",
                    [0.15, -0.2],
                    0.03,
                    WrapSide::Inside,
                    Motion::idler(5e-4),
                ),
            ],
            Section::default(),
            310.0,
        )
    }
}

/// A uniform mesh of element length `h` \[m\] on spans and wraps (the rotating mesh needs it)
/// with the default reduction.
pub fn uniform(h: f64) -> FlowingSettings {
    FlowingSettings {
        mesh: BeltMesh {
            span_element: h,
            arc_element: h,
            contact_margin_nodes: 1,
        },
        reduction: BeltReduction::default(),
        ..FlowingSettings::default()
    }
}

/// The flowing model of `layout` with `settings` (resolved first).
pub fn flowing(layout: &Layout, settings: &FlowingSettings) -> (FlowingBelt, belt::Drive) {
    let drive = layout.resolve().unwrap();
    (FlowingBelt::new(&drive, settings).unwrap(), drive)
}

/// The nodal model of `layout` on the mesh of `settings` (resolved first).
pub fn nodal(layout: &Layout, settings: &FlowingSettings) -> (NodalBelt, belt::Drive) {
    let drive = layout.resolve().unwrap();
    (NodalBelt::new(&drive, &settings.mesh).unwrap(), drive)
}

/// The FEAD study on [`triangle`] with the uniform mesh `h` \[m\] for the flowing and nodal
/// models: the driven pulley (J 0.013 kg m²) loaded with 5 N m (ramped in 0.1 s), the idler on
/// a tensioner arm, one engine speed (1000 rpm) with the default engine orders and the study's
/// default time stepping (0.25 ms, ρ∞ = 0.8, 0.1 s ramp, settle and window).
pub fn fead_triangle(h: f64) -> drives::fead::FeadConfig {
    use drives::fead::{EngineConfig, FeadConfig};
    let mut drive = triangle();
    drive.pulleys[1].motion = Motion::load(0.013, ramp(5.0));
    // the idler at the arm's end, 60 mm left of the pivot; the spring holds the belt's pull
    // (≈ 2 T sin(97°/2) ≈ 464 N upward, 28 N m about the pivot)
    drive.tensioner = Some(Tensioner {
        pulley: 2,
        pivot: [0.21, -0.2],
        stiffness: 30.0,
        preload: 28.0,
        preload_angle: std::f64::consts::PI,
        damping: 0.5,
        dry_friction: 0.0,
        friction_rate: 0.01,
        inertia: 2e-3,
        travel: [2.6, 3.6],
    });
    let mut c = FeadConfig {
        drive,
        engine: EngineConfig {
            speeds_rpm: vec![1000.0],
            ..Default::default()
        },
        ..Default::default()
    };
    c.models.flowing = uniform(h);
    c.models.nodal.mesh = uniform(h).mesh;
    c
}

/// A constant signal's shape (for comparisons).
pub fn constant(y: f64) -> Shape {
    Shape::Constant(y)
}
