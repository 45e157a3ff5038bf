//! Layouts shared by the layout tests (flowing `layout.rs`, nodal `layout_nodal.rs`, ANCF
//! `ancf_layout.rs`); each test file uses some of them.
#![allow(dead_code)]

use drives::layout::{LayoutConfig, LayoutMesh, LayoutPulley, MotionSpec};
use fe_model::generate::belt_path::WrapSide;
use flowing::belt::config::{BeltContact, BeltDamping, BeltReduction, BeltSection};
use flowing::belt::{BeltDriveConfig, Schedule, Signal};
use mbd_core::tensioner::TensionerSpec;

/// Crank (ramped to 80 rad/s in 0.1 s), alternator and water pump (each loaded with `load`
/// \[N m\], ramped in 0.1 s), back-side idler on a tensioner arm.
pub fn four_pulleys(load: f64) -> LayoutConfig {
    let load = |j: f64| MotionSpec::Load {
        inertia: j,
        torque: Signal {
            schedule: Schedule {
                knots: vec![(0.0, 0.0), (0.1, load)],
            },
            ..Default::default()
        },
    };
    LayoutConfig {
        pulleys: vec![
            LayoutPulley::new(
                "crank",
                [0.0, 0.0],
                0.075,
                WrapSide::Inside,
                MotionSpec::Speed {
                    speed: Signal {
                        schedule: Schedule {
                            knots: vec![(0.0, 0.0), (0.1, 80.0)],
                        },
                        ..Default::default()
                    },
                },
            ),
            LayoutPulley::new(
                "alternator",
                [0.12, 0.28],
                0.03,
                WrapSide::Inside,
                load(0.003),
            ),
            LayoutPulley::new(
                "tensioner",
                [0.16, 0.10],
                0.035,
                WrapSide::Outside,
                MotionSpec::Idler { inertia: 1e-4 },
            ),
            LayoutPulley::new(
                "water pump",
                [0.25, -0.05],
                0.05,
                WrapSide::Inside,
                load(0.002),
            ),
        ],
        tensioner: Some(TensionerSpec {
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
        }),
        belt: BeltSection::default(),
        belt_length: None,
        mesh: LayoutMesh {
            span_element: 0.04,
            arc_element: 0.012,
            contact_margin_nodes: 1,
        },
        contact: BeltContact::default(),
        damping: BeltDamping::default(),
        reduction: BeltReduction {
            free_modes: Some(12),
        },
    }
}

/// Driver (R 50 mm) and driven (R 50 mm, J of Table 6-1) 0.3 m apart, an idler (R 30 mm)
/// below them closing a triangle; the Table 6-1 belt, contact and damping, a uniform mesh of
/// element length `h` \[m\] on spans and wraps (the rotating mesh needs it).
pub fn triangle(h: f64) -> LayoutConfig {
    let base = BeltDriveConfig::default();
    LayoutConfig {
        pulleys: vec![
            LayoutPulley::new(
                "driver",
                [0.0, 0.0],
                0.05,
                WrapSide::Inside,
                MotionSpec::Speed {
                    speed: Signal::constant(0.0),
                },
            ),
            LayoutPulley::new(
                "driven",
                [0.3, 0.0],
                0.05,
                WrapSide::Inside,
                MotionSpec::Load {
                    inertia: base.driven_inertia,
                    torque: Signal::constant(0.0),
                },
            ),
            LayoutPulley::new(
                "idler",
                [0.15, -0.2],
                0.03,
                WrapSide::Inside,
                MotionSpec::Idler { inertia: 5e-4 },
            ),
        ],
        tensioner: None,
        belt: BeltSection::default(),
        belt_length: None,
        mesh: LayoutMesh {
            span_element: h,
            arc_element: h,
            contact_margin_nodes: 1,
        },
        contact: BeltContact::default(),
        damping: BeltDamping::default(),
        reduction: BeltReduction::default(),
    }
}

/// The FEAD study on [`triangle`]`(h)`: the driven pulley (J 0.013 kg m²) loaded with 5 N m
/// (ramped in 0.1 s), the idler on a tensioner arm, one engine speed (1000 rpm) with the
/// default engine orders and the study's default time stepping (0.25 ms, ρ∞ = 0.8, 0.1 s ramp,
/// settle and window).
pub fn fead_triangle(h: f64) -> drives::fead::FeadConfig {
    use drives::fead::{EngineConfig, FeadConfig};
    let mut drive = triangle(h);
    drive.pulleys[1].motion = MotionSpec::Load {
        inertia: 0.013,
        torque: Signal {
            schedule: Schedule {
                knots: vec![(0.0, 0.0), (0.1, 5.0)],
            },
            ..Default::default()
        },
    };
    // the idler at the arm's end, 60 mm left of the pivot; the spring holds the belt's pull
    // (≈ 2 T sin(97°/2) ≈ 464 N upward, 28 N m about the pivot)
    drive.tensioner = Some(TensionerSpec {
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
    FeadConfig {
        drive,
        engine: EngineConfig {
            speeds_rpm: vec![1000.0],
            ..Default::default()
        },
        ..Default::default()
    }
}
