//! Kinematics of the sagittal-plane segment tree in generalized coordinates
//! `q = [x, z, φ₀, φ₁, …]`: the root's reference point (the seat point) moves by `(x, z)` relative
//! to the seat frame, and every segment `s` pitches by the absolute angle `φ_s` from its design
//! posture. Pitch is a rotation about the y axis (ISO 2631-1 basicentric axes: x forward, y left,
//! z up), so a positive pitch tips the top of an upright segment forward.
//!
//! Why absolute angles: the mass matrix stays small and well conditioned, every point is an
//! explicit function of `q`, and a joint spring acts on `φ_child − φ_parent` like a link between
//! two coordinates. A point `P` of segment `s` is `P = O_root + Σ_u R(φ_u)·a_u` over the segments
//! `u` on the path from the root to `s`, where `a_u` is the design vector from `u`'s origin to the
//! next origin on the path (to `P` for `u = s`). Each term depends on one angle only, so
//! `∂P/∂φ_u = R′(b_u)` with `b_u = R(φ_u)·a_u` and `R′(v) = (v_z, −v_x)`, and the only second
//! derivatives are `∂²P/∂φ_u² = −b_u`.

use super::segment::Segment;

/// Index of the pitch coordinate of segment `s` in `q`.
pub fn pitch_dof(s: usize) -> usize {
    2 + s
}

/// Rotation of a seat-frame vector by pitch `phi` (rad) about y.
pub fn rotate(v: [f64; 2], phi: f64) -> [f64; 2] {
    let (s, c) = phi.sin_cos();
    [v[0] * c + v[1] * s, -v[0] * s + v[1] * c]
}

/// `dR/dφ` applied to an already rotated vector: `(v_z, −v_x)`.
pub fn rotate_rate(v: [f64; 2]) -> [f64; 2] {
    [v[1], -v[0]]
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn add(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] + b[0], a[1] + b[1]]
}

/// The segment tree at its design posture (parents before children, root first).
#[derive(Debug, Clone, PartialEq)]
pub struct Posture {
    /// Segments in tree order.
    pub segments: Vec<Segment>,
    /// Design position of the root's reference point (the seat point), m.
    pub reference: [f64; 2],
}

/// Where the segments are for a given `q`: each segment's origin (joint, or the reference point of
/// the root) and pitch.
#[derive(Debug, Clone)]
pub struct Placement {
    /// Current origin of each segment, m.
    pub origin: Vec<[f64; 2]>,
    /// Current absolute pitch change of each segment, rad.
    pub pitch: Vec<f64>,
}

impl Posture {
    /// Number of generalized coordinates `2 + segments`.
    pub fn dof(&self) -> usize {
        2 + self.segments.len()
    }

    /// Design origin of segment `s`: its joint to the parent, or the reference point for the root.
    pub fn design_origin(&self, s: usize) -> [f64; 2] {
        match self.segments[s].parent {
            None => self.reference,
            Some(_) => self.segments[s].from,
        }
    }

    /// Segments from the root to `s` (inclusive), root first.
    pub fn path(&self, s: usize) -> Vec<usize> {
        let mut p = vec![s];
        while let Some(parent) = self.segments[*p.last().expect("path")].parent {
            p.push(parent);
        }
        p.reverse();
        p
    }

    /// Places every segment for coordinates `q`.
    pub fn place(&self, q: &[f64]) -> Placement {
        let n = self.segments.len();
        let mut origin = vec![[0.0; 2]; n];
        let mut pitch = vec![0.0; n];
        for s in 0..n {
            pitch[s] = q[pitch_dof(s)];
            origin[s] = match self.segments[s].parent {
                None => add(self.reference, [q[0], q[1]]),
                Some(p) => add(
                    origin[p],
                    rotate(sub(self.segments[s].from, self.design_origin(p)), pitch[p]),
                ),
            };
        }
        Placement { origin, pitch }
    }

    /// Current position of the body point designed at `p0` on segment `s`.
    pub fn point(&self, pl: &Placement, s: usize, p0: [f64; 2]) -> [f64; 2] {
        add(
            pl.origin[s],
            rotate(sub(p0, self.design_origin(s)), pl.pitch[s]),
        )
    }

    /// Jacobian (2 × dof, row-major: `[dx/dq; dz/dq]`) of the point designed at `p0` on segment `s`.
    pub fn jacobian(&self, pl: &Placement, s: usize, p0: [f64; 2]) -> [Vec<f64>; 2] {
        let n = self.dof();
        let p = self.point(pl, s, p0);
        let mut j = [vec![0.0; n], vec![0.0; n]];
        j[0][0] = 1.0;
        j[1][1] = 1.0;
        for (u, b) in self.arms(pl, s, p) {
            let d = rotate_rate(b);
            j[0][pitch_dof(u)] = d[0];
            j[1][pitch_dof(u)] = d[1];
        }
        j
    }

    /// The current arm vectors `b_u` of the point `p` (current position) on segment `s`.
    fn arms(&self, pl: &Placement, s: usize, p: [f64; 2]) -> Vec<(usize, [f64; 2])> {
        let path = self.path(s);
        path.iter()
            .enumerate()
            .map(|(k, &u)| {
                let end = path.get(k + 1).map_or(p, |&next| pl.origin[next]);
                (u, sub(end, pl.origin[u]))
            })
            .collect()
    }

    /// Adds `Σ_u g · ∂²P/∂φ_u²` (the geometric stiffness of a force `−g` acting at the point
    /// designed at `p0` on segment `s`, with `g = ∂V/∂P`) into the row-major `dof × dof` matrix `k`.
    pub fn add_geometric(
        &self,
        pl: &Placement,
        s: usize,
        p0: [f64; 2],
        g: [f64; 2],
        k: &mut [f64],
    ) {
        let n = self.dof();
        let p = self.point(pl, s, p0);
        for (u, b) in self.arms(pl, s, p) {
            k[pitch_dof(u) * n + pitch_dof(u)] -= g[0] * b[0] + g[1] * b[1];
        }
    }
}
