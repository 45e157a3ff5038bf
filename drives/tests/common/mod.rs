//! Layouts shared by the layout tests (flowing `layout.rs`, ANCF `ancf_layout.rs`).

use drives::layout::{LayoutConfig, LayoutMesh, LayoutPulley, MotionSpec};
use fe_model::generate::belt_path::WrapSide;
use flowing::belt::config::{BeltContact, BeltDamping, BeltReduction, BeltSection};
use flowing::belt::{Schedule, Signal};
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
