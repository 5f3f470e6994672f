//! Near-plane clipping of triangles in clip space (Sutherland–Hodgman against
//! one plane).

/// A vertex in clip space with `K` attributes interpolated linearly in clip space
/// (eye position, normal, colour, texture coordinates…).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClipVertex<const K: usize> {
    /// Clip coordinates `(x_c, y_c, z_c, w_c)`.
    pub clip: [f32; 4],
    /// Attributes.
    pub attrs: [f32; K],
}

impl<const K: usize> Default for ClipVertex<K> {
    fn default() -> Self {
        Self {
            clip: [0.0; 4],
            attrs: [0.0; K],
        }
    }
}

impl<const K: usize> ClipVertex<K> {
    /// `a + t·(b − a)` for every coordinate and attribute.
    fn lerp(&self, b: &Self, t: f32) -> Self {
        let mut out = *self;
        for (o, &v) in out.clip.iter_mut().zip(&b.clip) {
            *o += t * (v - *o);
        }
        for (o, &v) in out.attrs.iter_mut().zip(&b.attrs) {
            *o += t * (v - *o);
        }
        out
    }
}

/// Clips triangle `tri` to the half-space `w_c ≥ near_w` and writes the result
/// as 0, 1 or 2 triangles to `out`; returns how many.
///
/// Sutherland–Hodgman against one plane: walking the edges `a → b`, a vertex
/// with `w_c ≥ near_w` is kept, and an edge whose ends lie on opposite
/// sides contributes the point `a + t·(b − a)`, `t = d_a/(d_a − d_b)`, with its
/// `w_c` set to exactly `near_w`. The resulting polygon (3 or 4 vertices) is
/// fanned from its first vertex, so the winding is kept. A triangle entirely in
/// front comes back unchanged as `out[0]`; one entirely behind gives 0.
///
/// Vertices with a NaN `w_c` count as behind; a NaN `near_w` clips everything.
/// Never panics.
///
/// ```
/// use fixshade::mesh::{clip_near, ClipVertex};
/// let v = |x: f32, w: f32, a: f32| ClipVertex { clip: [x, 0.0, 0.0, w], attrs: [a] };
/// // vertex 0 behind w = 1: a quad remains, as two triangles
/// let tri = [v(0.0, 0.0, 0.0), v(1.0, 2.0, 1.0), v(2.0, 2.0, 2.0)];
/// let mut out = [[ClipVertex::default(); 3]; 2];
/// assert_eq!(clip_near(&tri, 1.0, &mut out), 2);
/// assert_eq!(out[0][0], v(0.5, 1.0, 0.5)); // halfway along 0 → 1
/// assert_eq!(out[1][2], v(1.0, 1.0, 1.0)); // halfway along 2 → 0
/// ```
pub fn clip_near<const K: usize>(
    tri: &[ClipVertex<K>; 3],
    near_w: f32,
    out: &mut [[ClipVertex<K>; 3]; 2],
) -> usize {
    let d = tri.map(|v| v.clip[3] - near_w);
    let inside = tri.map(|v| v.clip[3] >= near_w);
    if inside == [true; 3] {
        out[0] = *tri;
        return 1;
    }
    let mut poly = [ClipVertex::<K>::default(); 4];
    let mut n = 0;
    for i in 0..3 {
        let j = (i + 1) % 3;
        if inside[i] && n < 4 {
            poly[n] = tri[i];
            n += 1;
        }
        if inside[i] != inside[j] && n < 4 {
            // d_i and d_j have opposite signs: t ∈ [0, 1]
            let t = d[i] / (d[i] - d[j]);
            let mut p = tri[i].lerp(&tri[j], t);
            p.clip[3] = near_w;
            poly[n] = p;
            n += 1;
        }
    }
    match n {
        3 => {
            out[0] = [poly[0], poly[1], poly[2]];
            1
        }
        4 => {
            out[0] = [poly[0], poly[1], poly[2]];
            out[1] = [poly[0], poly[2], poly[3]];
            2
        }
        _ => 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f32, y: f32, w: f32) -> ClipVertex<2> {
        ClipVertex {
            clip: [x, y, 0.0, w],
            attrs: [x, w],
        }
    }

    /// Twice the signed area of the triangle's (x/w, y/w) projection.
    fn area(t: &[ClipVertex<2>; 3]) -> f32 {
        let p = t.map(|v| [v.clip[0] / v.clip[3], v.clip[1] / v.clip[3]]);
        (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1])
    }

    #[test]
    fn all_in_front_all_behind() {
        let tri = [v(0.0, 0.0, 2.0), v(1.0, 0.0, 3.0), v(0.0, 1.0, 1.0)];
        let mut out = [[ClipVertex::default(); 3]; 2];
        assert_eq!(clip_near(&tri, 1.0, &mut out), 1);
        assert_eq!(out[0], tri);
        let behind = [v(0.0, 0.0, 0.5), v(1.0, 0.0, -3.0), v(0.0, 1.0, 0.99)];
        assert_eq!(clip_near(&behind, 1.0, &mut out), 0);
        assert_eq!(clip_near(&tri, f32::NAN, &mut out), 0);
    }

    #[test]
    fn one_vertex_in_front() {
        // vertex 1 in front at w = 3, the others at w = −1: the edges are cut at
        // t = ½ (from vertex 1)
        let tri = [v(0.0, 0.0, -1.0), v(4.0, 0.0, 3.0), v(0.0, 4.0, -1.0)];
        let mut out = [[ClipVertex::default(); 3]; 2];
        assert_eq!(clip_near(&tri, 1.0, &mut out), 1);
        assert_eq!(
            out[0],
            [v(2.0, 0.0, 1.0), v(4.0, 0.0, 3.0), v(2.0, 2.0, 1.0)]
        );
    }

    #[test]
    fn winding_is_kept() {
        for rot in 0..3 {
            for behind in 0..3 {
                let mut tri = [v(-1.0, -1.0, 2.0), v(1.0, -1.0, 2.0), v(0.0, 1.0, 2.0)];
                tri[behind].clip[3] = 0.5;
                tri[behind].attrs[1] = 0.5;
                tri.rotate_left(rot);
                let sign = area(&tri).signum();
                let mut out = [[ClipVertex::default(); 3]; 2];
                let n = clip_near(&tri, 1.0, &mut out);
                assert_eq!(n, 2);
                for t in &out[..n] {
                    assert_eq!(area(t).signum(), sign);
                    for p in t {
                        assert!(p.clip[3] >= 1.0);
                        // attrs[1] tracks w: linear interpolation is exact
                        assert!((p.attrs[1] - p.clip[3]).abs() < 1e-6);
                    }
                }
            }
        }
    }
}
