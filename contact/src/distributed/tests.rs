use super::*;
use crate::friction::{CoulombTanh, Frictionless, Stribeck};
use crate::geometry::Disk;
use crate::normal::LinearPenalty;
use crate::quadrature::GaussRule;
use crate::spatial::{Cylinder, HalfSpace};
use nalgebra::{Point2, Point3, Vector2, Vector3};

/// Largest absolute entry.
fn amax(x: &[f64]) -> f64 {
    x.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

/// Largest absolute component of a list of moments.
fn amax3(x: &[Vector3<f64>]) -> f64 {
    x.iter().fold(0.0f64, |m, v| m.max(v.amax()))
}

/// Bilinear 4-node surface element (3 coordinates per node, node `i + 2j` at `(ξ_i, η_j)`):
/// quadrature points of the tensor Gauss rule with a constant area Jacobian `area`.
fn bilinear_points(
    e: &SVector<f64, 12>, edot: &SVector<f64, 12>, rule_xi: &GaussRule, rule_eta: &GaussRule,
    area: f64,
) -> Vec<QuadPoint<3, SMatrix<f64, 3, 12>>> {
    let mut out = Vec::new();
    for (eta, we) in rule_eta.iter() {
        for (xi, wx) in rule_xi.iter() {
            let n = [
                (1.0 - xi) * (1.0 - eta),
                xi * (1.0 - eta),
                (1.0 - xi) * eta,
                xi * eta,
            ];
            let mut s = SMatrix::<f64, 3, 12>::zeros();
            for k in 0..4 {
                for a in 0..3 {
                    s[(a, 3 * k + a)] = n[k];
                }
            }
            out.push(QuadPoint {
                position: Point3::from(s * e),
                velocity: s * edot,
                shape: s,
                weight: wx * we * area,
            });
        }
    }
    out
}

fn pulley(omega: f64) -> Cylinder {
    Cylinder {
        center: Point3::new(0.0, 0.0, 0.0),
        axis: Vector3::new(0.1, 0.0, 1.0).normalize(),
        radius: 0.1,
        crown: 0.5,
        velocity: Vector3::new(0.02, -0.01, 0.0),
        omega,
    }
}

/// Coordinates and velocities of a bilinear element pressed onto [`pulley`] (radius 0.098 m,
/// the corners 0.1 mm deeper each, θ from 0.05 to 0.35 rad, z from −0.01 to 0.015 m), moving
/// near the surface speed ωR = 2 m/s with some slip and out-of-plane motion.
fn pressed_element() -> (SVector<f64, 12>, SVector<f64, 12>) {
    let r = 0.098;
    let (th0, th1, z0, z1): (f64, f64, f64, f64) = (0.05, 0.35, -0.01, 0.015);
    let mut e = SVector::<f64, 12>::zeros();
    let mut edot = SVector::<f64, 12>::zeros();
    for (k, (th, z)) in [(th0, z0), (th1, z0), (th0, z1), (th1, z1)]
        .into_iter()
        .enumerate()
    {
        let rr = r + 1e-4 * k as f64;
        e.fixed_rows_mut::<3>(3 * k)
            .copy_from(&Vector3::new(rr * th.cos(), rr * th.sin(), z));
        edot.fixed_rows_mut::<3>(3 * k).copy_from(&Vector3::new(
            -1.97 * th.sin() + 0.01 * k as f64,
            1.97 * th.cos(),
            0.03 - 0.02 * k as f64,
        ));
    }
    (e, edot)
}

// Reference (second formulation): central differences of the element force and moment in the
// coordinates, the velocities and the pulley's angular velocity.
#[test]
fn tangent_matches_finite_differences() {
    let pair = SurfaceContact {
        surface: pulley(20.0),
        normal: LinearPenalty {
            stiffness: 1e9,
            damping: 1e3,
        },
        friction: Stribeck {
            mu_static: 0.6,
            mu_kinetic: 0.4,
            stribeck_velocity: 0.05,
            kappa: 40.0,
        },
    };
    let (e, edot) = pressed_element();
    let rule = GaussRule::new(3);
    let eval = |e: &SVector<f64, 12>, edot: &SVector<f64, 12>, w: f64| {
        let mut out = ElementContact::<3>::new(12);
        let pts = bilinear_points(e, edot, &rule, &rule, 0.03 * 0.025);
        element_contact(
            &pulley(w),
            &pair.normal,
            &pair.friction,
            pts,
            true,
            &mut out,
            None,
        );
        out
    };
    let c = eval(&e, &edot, 20.0);
    assert_eq!(c.active_points, 9);
    let tol = |m: f64| 1e-6 * m;
    let (sk, sc, smk, smc) = (
        amax(&c.dq_de),
        amax(&c.dq_dedot),
        amax3(&c.dmoment_de),
        amax3(&c.dmoment_dedot),
    );
    for j in 0..12 {
        let h = 1e-8;
        let mut d = SVector::<f64, 12>::zeros();
        d[j] = h;
        let (p, m) = (eval(&(e + d), &edot, 20.0), eval(&(e - d), &edot, 20.0));
        let (pv, mv) = (eval(&e, &(edot + d), 20.0), eval(&e, &(edot - d), 20.0));
        for i in 0..12 {
            let fd = (p.q[i] - m.q[i]) / (2.0 * h);
            assert!((fd - c.dq_de[i + 12 * j]).abs() < tol(sk), "dQ{i}/de{j}");
            let fd = (pv.q[i] - mv.q[i]) / (2.0 * h);
            assert!(
                (fd - c.dq_dedot[i + 12 * j]).abs() < tol(sc),
                "dQ{i}/dedot{j}"
            );
        }
        for i in 0..3 {
            let fd = (p.moment[i] - m.moment[i]) / (2.0 * h);
            assert!((fd - c.dmoment_de[j][i]).abs() < tol(smk), "dM{i}/de{j}");
            let fd = (pv.moment[i] - mv.moment[i]) / (2.0 * h);
            assert!(
                (fd - c.dmoment_dedot[j][i]).abs() < tol(smc),
                "dM{i}/dedot{j}"
            );
        }
    }
    let h = 1e-6;
    let (p, m) = (eval(&e, &edot, 20.0 + h), eval(&e, &edot, 20.0 - h));
    for i in 0..12 {
        let fd = (p.q[i] - m.q[i]) / (2.0 * h);
        assert!((fd - c.dq_domega[i]).abs() < tol(amax(&c.dq_domega)));
    }
    let fd = (p.moment - m.moment) / (2.0 * h);
    assert!((fd - c.dmoment_domega).amax() < tol(c.dmoment_domega.amax()));
    // the generalized forces carry the resultant: Σ over nodes of Q = −F (partition of unity)
    let mut sum = Vector3::zeros();
    for k in 0..4 {
        sum += Vector3::from_column_slice(&c.q[3 * k..3 * k + 3]);
    }
    assert!((sum + c.reaction).amax() < 1e-12 * c.reaction.amax());
}

// Reference: analytical — a flat plate at uniform penetration δ in a half-space carries
// F = k δ A, with the centre of pressure at the plate centroid.
#[test]
fn flat_plate_in_half_space() {
    let (k, delta, a, b) = (2.5e8, 3e-4, 0.04, 0.015);
    let pair = SurfaceContact {
        surface: HalfSpace {
            origin: Point3::new(0.0, 0.0, 0.0),
            normal: Vector3::z(),
            tangent: Vector3::x(),
            velocity: Vector3::zeros(),
        },
        normal: LinearPenalty {
            stiffness: k,
            damping: 50.0,
        },
        friction: Frictionless,
    };
    let (x0, y0) = (0.3, -0.2);
    let mut e = SVector::<f64, 12>::zeros();
    for (kk, (x, y)) in [(x0, y0), (x0 + a, y0), (x0, y0 + b), (x0 + a, y0 + b)]
        .into_iter()
        .enumerate()
    {
        e.fixed_rows_mut::<3>(3 * kk)
            .copy_from(&Vector3::new(x, y, -delta));
    }
    let rule = GaussRule::new(9);
    let mut out = ElementContact::<3>::new(12);
    let mut rec = Vec::new();
    pair.element(
        bilinear_points(&e, &SVector::zeros(), &rule, &rule, a * b),
        true,
        &mut out,
        Some(&mut rec),
    );
    assert_eq!(out.active_points, 81);
    assert_eq!(rec.len(), 81);
    let total = k * delta * a * b;
    assert!((out.reaction.z + total).abs() < 1e-12 * total);
    assert!(out.reaction.xy().amax() < 1e-12 * total);
    let mut fz = 0.0;
    for kk in 0..4 {
        // uniform pressure: a quarter of the load per node
        assert!((out.q[3 * kk + 2] - 0.25 * total).abs() < 1e-12 * total);
        fz += out.q[3 * kk + 2];
    }
    assert!((fz - total).abs() < 1e-12 * total);
    let centroid = Vector3::new(x0 + 0.5 * a, y0 + 0.5 * b, -delta);
    let m = centroid.cross(&out.reaction);
    assert!((m - out.moment).amax() < 1e-12 * total);
    assert!(
        rec.iter()
            .all(|r| (r.normal_force - k * delta).abs() < 1e-9)
    );
}

// Reference (second formulation): the planar line contact on a disk (Kerkkänen (3.27)) and
// the spatial contact of the same element extruded over a width `b` on a straight cylinder,
// with no out-of-plane motion, give the same force and torque per unit width.
#[test]
fn planar_line_contact_equals_extruded_plate() {
    let (k, c) = (1e7, 10.0);
    let fl = CoulombTanh {
        mu: 1.2,
        kappa: 40.0,
    };
    let omega = 20.0;
    let disk = Disk {
        center: Point2::new(0.01, -0.02),
        radius: 0.1,
        velocity: Vector2::zeros(),
        omega,
    };
    let rule = GaussRule::new(5);
    let planar = LineContact {
        surface: disk,
        normal: LinearPenalty {
            stiffness: k,
            damping: c,
        },
        friction: fl,
        rule: rule.clone(),
    };
    let spatial = SurfaceContact {
        surface: Cylinder {
            center: Point3::new(0.01, -0.02, 0.0),
            axis: Vector3::z(),
            radius: 0.1,
            crown: 0.0,
            velocity: Vector3::zeros(),
            omega,
        },
        normal: LinearPenalty {
            stiffness: k,
            damping: c,
        },
        friction: fl,
    };
    let nodes: [[f64; 2]; 2] = [
        [0.01 + 0.0996, -0.02 + 0.004],
        [0.01 + 0.088, -0.02 + 0.047],
    ];
    let vels = [[-0.09, 1.99], [-0.93, 1.77]];
    let e2 = [nodes[0][0], nodes[0][1], nodes[1][0], nodes[1][1]];
    let v2 = [vels[0][0], vels[0][1], vels[1][0], vels[1][1]];
    let length = ((nodes[1][0] - nodes[0][0]).powi(2) + (nodes[1][1] - nodes[0][1]).powi(2)).sqrt();
    let mut out2 = ElementContact::<2>::new(4);
    planar.element(
        length,
        2,
        |xi, s| {
            s[0] = 1.0 - xi;
            s[1] = xi;
        },
        &e2,
        &v2,
        true,
        &mut out2,
        None,
    );
    assert!(out2.active_points > 0);
    let b = 0.6;
    let mut e3 = SVector::<f64, 12>::zeros();
    let mut v3 = SVector::<f64, 12>::zeros();
    for j in 0..2 {
        for i in 0..2 {
            let kk = i + 2 * j;
            let z = (j as f64 - 0.5) * b;
            e3.fixed_rows_mut::<3>(3 * kk)
                .copy_from(&Vector3::new(nodes[i][0], nodes[i][1], z));
            v3.fixed_rows_mut::<3>(3 * kk)
                .copy_from(&Vector3::new(vels[i][0], vels[i][1], 0.0));
        }
    }
    let mut out3 = ElementContact::<3>::new(12);
    spatial.element(
        bilinear_points(&e3, &v3, &rule, &GaussRule::new(2), length * b),
        true,
        &mut out3,
        None,
    );
    assert_eq!(out3.active_points, 2 * out2.active_points);
    let scale = amax(&out2.q);
    for i in 0..2 {
        for a in 0..2 {
            let per_width = (out3.q[3 * i + a] + out3.q[3 * (i + 2) + a]) / b;
            assert!(
                (per_width - out2.q[2 * i + a]).abs() < 1e-12 * scale,
                "Q[{i}][{a}]: {per_width} vs {}",
                out2.q[2 * i + a]
            );
        }
        assert!(out3.q[3 * i + 2].abs() < 1e-12 * scale);
    }
    assert!((out3.moment.z / b - out2.moment).abs() < 1e-12 * out2.moment.abs());
    assert!((out3.reaction.x / b - out2.reaction[0]).abs() < 1e-12 * scale);
    assert!((out3.reaction.y / b - out2.reaction[1]).abs() < 1e-12 * scale);
    // the in-plane stiffness per width, node block (0,0)
    let sk = amax(&out2.dq_de);
    for a in 0..2 {
        for bb in 0..2 {
            let k3 = (0..2)
                .map(|j| {
                    (0..2)
                        .map(|l| out3.dq_de[(3 * 2 * j + a) + 12 * (3 * 2 * l + bb)])
                        .sum::<f64>()
                })
                .sum::<f64>()
                / b;
            assert!((k3 - out2.dq_de[a + bb * 4]).abs() < 1e-12 * sk);
        }
    }
}

// Reference (second formulation): the block-shape path (pair sums of
// `add_block_congruences`, force-only points through `Surface::closest_value`) against the
// general matrix path (`Sᵀ A S` point by point with the full 3 × 12 shape matrix) on the same
// bilinear element pressed onto a crowned, rotating pulley; the forces of a force-only pass
// equal those of the pass with Jacobians bit for bit.
#[test]
fn block_shapes_equal_the_general_shape_matrix() {
    let normal = LinearPenalty {
        stiffness: 1e9,
        damping: 1e3,
    };
    let friction = Stribeck {
        mu_static: 0.6,
        mu_kinetic: 0.4,
        stribeck_velocity: 0.05,
        kappa: 40.0,
    };
    let (e, edot) = pressed_element();
    let rule = GaussRule::new(3);
    let full = bilinear_points(&e, &edot, &rule, &rule, 0.03 * 0.025);
    // the same points with the block shape [n_k I₃]: n_k = S[(0, 3k)]
    let blocks: Vec<QuadPoint<3, BlockShape>> = full
        .iter()
        .map(|p| {
            let mut values = [0.0; MAX_BLOCKS];
            for (k, v) in values.iter_mut().take(4).enumerate() {
                *v = p.shape[(0, 3 * k)];
            }
            QuadPoint {
                position: p.position,
                velocity: p.velocity,
                shape: BlockShape { values, blocks: 4 },
                weight: p.weight,
            }
        })
        .collect();
    let surf = pulley(20.0);
    let mut a = ElementContact::<3>::new(12);
    let mut b = ElementContact::<3>::new(12);
    let mut f = ElementContact::<3>::new(12);
    element_contact(&surf, &normal, &friction, full, true, &mut a, None);
    element_contact(
        &surf,
        &normal,
        &friction,
        blocks.clone(),
        true,
        &mut b,
        None,
    );
    // the batch path: the same block shapes and weights as a `BlockQuadrature`
    let shapes: Vec<[f64; MAX_BLOCKS]> = blocks.iter().map(|p| p.shape.values).collect();
    let quad = BlockQuadrature::new(
        4,
        shapes.iter().zip(&blocks).map(|(s, p)| (&s[..4], p.weight)),
    );
    let mut g = ElementContact::<3>::new(12);
    element_forces_blocks(
        &surf,
        &normal,
        &friction,
        &quad,
        e.as_slice(),
        edot.as_slice(),
        &mut g,
    );
    element_contact(&surf, &normal, &friction, blocks, false, &mut f, None);
    assert!(a.active_points > 0, "{}", a.active_points);
    assert_eq!(a.active_points, b.active_points);
    let close = |x: &[f64], y: &[f64]| {
        let scale = amax(x);
        x.iter().zip(y).all(|(u, v)| (u - v).abs() <= 1e-12 * scale)
    };
    assert!(close(&a.q, &b.q));
    assert!(close(&a.dq_de, &b.dq_de));
    assert!(close(&a.dq_dedot, &b.dq_dedot));
    assert!(close(&a.dq_domega, &b.dq_domega));
    assert!(amax3(&a.dmoment_de) > 0.0);
    for (u, v) in a.dmoment_de.iter().zip(&b.dmoment_de) {
        assert!((u - v).amax() <= 1e-12 * amax3(&a.dmoment_de));
    }
    // the force-only pass: the same forces, moment and reaction, no Jacobians
    assert_eq!(f.q, b.q);
    assert_eq!(f.moment, b.moment);
    assert_eq!(f.reaction, b.reaction);
    assert!(f.dq_de.iter().all(|v| *v == 0.0));
    // the batch: the same points in contact and forces (its positions Σ_b s_b e_b are summed in
    // another order than the matrix product `S e` of the points above: round-off apart)
    assert_eq!(g.active_points, f.active_points);
    assert!(close(&f.q, &g.q));
    assert!((f.moment - g.moment).amax() <= 1e-12 * f.moment.amax());
    assert!((f.reaction - g.reaction).amax() <= 1e-12 * f.reaction.amax());
    assert!(g.dq_de.iter().all(|v| *v == 0.0));
}

// Reference (the previous formulation): the pair sums of `add_block_congruences` taken point
// by point (each point's `s_i s_j m` added to every pair's stored sum, the loop order before
// the sums were held per pair) on 81 records of 12 blocks with irregular values: the same bits,
// since every sum adds the same products in the same order.
#[test]
fn pair_sums_per_pair_equal_the_point_by_point_sums() {
    let (blocks, nc) = (12, 18);
    let points: Vec<f64> = (0..81 * (blocks + nc))
        .map(|k| (0.37 * k as f64).sin() * (1.0 + (k % 7) as f64))
        .collect();
    let pairs = blocks * (blocks + 1) / 2;
    let mut reference = vec![0.0; pairs * nc];
    for rec in points.chunks_exact(blocks + nc) {
        let (s, m) = rec.split_at(blocks);
        let mut rows = reference.chunks_exact_mut(nc);
        for j in 0..blocks {
            for i in 0..=j {
                let t = s[i] * s[j];
                for (r, v) in rows.next().unwrap().iter_mut().zip(m) {
                    *r += t * v;
                }
            }
        }
    }
    let mut acc = vec![0.0; pairs * nc];
    super::pair_sums::<3>(blocks, &points, &mut acc);
    assert!(reference.iter().any(|v| *v != 0.0));
    assert!(
        reference
            .iter()
            .zip(&acc)
            .all(|(a, b)| a.to_bits() == b.to_bits())
    );
}

/// The plate belt's contact laws: linear penalty with damping and the creep-rate friction.
fn plate_laws() -> (crate::normal::NormalSpec, crate::friction::FrictionSpec) {
    (
        crate::normal::NormalSpec::penalty(1e9, 0.0, 1e3),
        crate::friction::FrictionSpec::CreepRate {
            mu: 0.6,
            creep: 2e5,
        },
    )
}

// Reference (the previous formulation): `element_contact`'s force-only pass, one point at a
// time through `point_force` (closest point, basis, normal law, friction law, `Sᵀ f`), on the
// plate belt's laws (linear penalty with damping `NormalSpec`, the creep-rate `FrictionSpec`)
// over a 9 × 3 grid, with the points' positions summed as the batch sums them
// (`r = Σ_b s_b e_b`). The batch forms every point's force with the same operations and adds
// every sum over the points in the same order, so the forces, moment and reaction are equal
// to the last bit; the three pulley speeds put the points on the creep branch (19.7 rad/s,
// slip of a few cm/s), on the saturated branch (200 rad/s) and in between.
#[test]
fn batch_forces_of_the_plate_laws_equal_the_point_by_point_pass() {
    let (normal, friction) = plate_laws();
    let (e, edot) = pressed_element();
    let (rx, ry) = (GaussRule::new(9), GaussRule::new(3));
    let area = 0.03 * 0.025;
    let mut shapes = Vec::new();
    let mut weights = Vec::new();
    for (eta, we) in ry.iter() {
        for (xi, wx) in rx.iter() {
            let mut v = [0.0; MAX_BLOCKS];
            v[..4].copy_from_slice(&[
                (1.0 - xi) * (1.0 - eta),
                xi * (1.0 - eta),
                (1.0 - xi) * eta,
                xi * eta,
            ]);
            shapes.push(v);
            weights.push(wx * we * area);
        }
    }
    let points: Vec<QuadPoint<3, BlockShape>> = shapes
        .iter()
        .zip(&weights)
        .map(|(v, &w)| {
            let (mut p, mut u) = (Point3::origin(), Vector3::zeros());
            for b in 0..4 {
                for i in 0..3 {
                    p[i] += v[b] * e[3 * b + i];
                    u[i] += v[b] * edot[3 * b + i];
                }
            }
            QuadPoint {
                position: p,
                velocity: u,
                shape: BlockShape {
                    values: *v,
                    blocks: 4,
                },
                weight: w,
            }
        })
        .collect();
    let quad = BlockQuadrature::new(4, shapes.iter().zip(&weights).map(|(s, &w)| (&s[..4], w)));
    for omega in [19.7, 25.0, 200.0] {
        let surf = pulley(omega);
        let mut reference = ElementContact::<3>::new(12);
        let mut records = Vec::new();
        element_contact(
            &surf,
            &normal,
            &friction,
            points.clone(),
            false,
            &mut reference,
            Some(&mut records),
        );
        let mut batch = ElementContact::<3>::new(12);
        element_forces_blocks(
            &surf,
            &normal,
            &friction,
            &quad,
            e.as_slice(),
            edot.as_slice(),
            &mut batch,
        );
        let saturated = records
            .iter()
            .filter(|r| (r.friction_force.norm() - 0.6 * r.normal_force.abs()).abs() < 1e-9)
            .count();
        println!(
            "ω = {omega}: {} of 27 points in contact, {saturated} saturated",
            reference.active_points
        );
        assert!(reference.active_points > 0);
        assert_eq!(
            saturated > 0,
            omega > 100.0,
            "ω = {omega}: {saturated} saturated"
        );
        assert_eq!(batch.active_points, reference.active_points);
        assert_eq!(batch.q, reference.q, "ω = {omega}");
        assert_eq!(batch.moment, reference.moment, "ω = {omega}");
        assert_eq!(batch.reaction, reference.reaction, "ω = {omega}");
    }
}

// Reference (the previous formulation): `element_contact`'s force-only pass, one point at a
// time, on an element of `MAX_BLOCKS` = 12 block shape functions (the plate's count, which
// takes the register-held sums of `BlockScatter`): bilinear corner functions `N_i` and the
// bubbles `N_i ξ(1 − ξ)`, `N_i η(1 − η)` with small coordinates, over a 9 × 3 grid, the
// element moved out radially by `lift` so that all (0), part (3 mm: the points beyond the
// crowned cylinder's radius are separated) or none (2 cm: the early exit of
// `element_forces_blocks`) of its points are in contact. Positions summed as the batch sums
// them (`r = Σ_b s_b e_b` from b = 0): the forces, moment, reaction and active count must be
// equal to the last bit.
#[test]
fn batch_forces_of_twelve_blocks_equal_the_point_by_point_pass_in_and_out_of_contact() {
    let (normal, friction) = plate_laws();
    let (e4, edot4) = pressed_element();
    let (rx, ry) = (GaussRule::new(9), GaussRule::new(3));
    let area = 0.03 * 0.025;
    let mut shapes = Vec::new();
    let mut weights = Vec::new();
    for (eta, we) in ry.iter() {
        for (xi, wx) in rx.iter() {
            let n = [
                (1.0 - xi) * (1.0 - eta),
                xi * (1.0 - eta),
                (1.0 - xi) * eta,
                xi * eta,
            ];
            let mut v = [0.0; MAX_BLOCKS];
            for i in 0..4 {
                v[i] = n[i];
                v[4 + i] = n[i] * xi * (1.0 - xi);
                v[8 + i] = n[i] * eta * (1.0 - eta);
            }
            shapes.push(v);
            weights.push(wx * we * area);
        }
    }
    let quad = BlockQuadrature::new(
        MAX_BLOCKS,
        shapes.iter().zip(&weights).map(|(s, &w)| (&s[..], w)),
    );
    let surf = pulley(25.0);
    let mut counts = Vec::new();
    for lift in [0.0, 3e-3, 2e-2] {
        let mut e = [0.0; 3 * MAX_BLOCKS];
        let mut edot = [0.0; 3 * MAX_BLOCKS];
        for b in 0..4 {
            let p = Vector3::new(e4[3 * b], e4[3 * b + 1], e4[3 * b + 2]);
            let radial = Vector3::new(p.x, p.y, 0.0).normalize() * lift;
            for i in 0..3 {
                e[3 * b + i] = p[i] + radial[i];
                edot[3 * b + i] = edot4[3 * b + i];
            }
        }
        for b in 4..MAX_BLOCKS {
            for i in 0..3 {
                e[3 * b + i] = 1e-3 * ((b * 3 + i) as f64 * 0.7).sin();
                edot[3 * b + i] = 1e-2 * ((b * 3 + i) as f64 * 1.3).cos();
            }
        }
        let points: Vec<QuadPoint<3, BlockShape>> = shapes
            .iter()
            .zip(&weights)
            .map(|(v, &w)| {
                let (mut p, mut u) = (Point3::origin(), Vector3::zeros());
                for b in 0..MAX_BLOCKS {
                    for i in 0..3 {
                        p[i] += v[b] * e[3 * b + i];
                        u[i] += v[b] * edot[3 * b + i];
                    }
                }
                QuadPoint {
                    position: p,
                    velocity: u,
                    shape: BlockShape {
                        values: *v,
                        blocks: MAX_BLOCKS,
                    },
                    weight: w,
                }
            })
            .collect();
        let mut reference = ElementContact::<3>::new(3 * MAX_BLOCKS);
        element_contact(
            &surf,
            &normal,
            &friction,
            points,
            false,
            &mut reference,
            None,
        );
        let mut batch = ElementContact::<3>::new(3 * MAX_BLOCKS);
        // twice through the same buffers: the second call must not see the first one's sums
        for _ in 0..2 {
            element_forces_blocks(&surf, &normal, &friction, &quad, &e, &edot, &mut batch);
            assert_eq!(batch.active_points, reference.active_points, "lift {lift}");
            let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&batch.q), bits(&reference.q), "lift {lift}");
            assert_eq!(batch.moment, reference.moment, "lift {lift}");
            assert_eq!(batch.reaction, reference.reaction, "lift {lift}");
        }
        counts.push(reference.active_points);
    }
    println!("points in contact at the three lifts: {counts:?} of 27");
    assert_eq!(counts[0], 27);
    assert!(counts[1] > 0 && counts[1] < 27, "{counts:?}");
    assert_eq!(counts[2], 0);
}
