//! Frames in the evaluation context: looking them up, building the frame
//! a `[[frame]]` table declares (Ω given, or derived from a parent and a
//! rotation), and carrying components along the chain of rotations.

use super::context::{Context, R};
use super::raw::RawFrame;
use super::value::Value;
use crate::atom::Atom;
use crate::frame::Frame;
use crate::parse::{Ast, AstKind, Span};
use crate::poly::Poly;
use crate::vector::{Mat3, Vec3};

impl Context<'_> {
    /// The frame called `name` (it exists: values only name known frames).
    pub fn frame(&self, name: &str) -> &Frame {
        &self.frames[self.frame_index(name).expect("frame exists")]
    }

    pub(crate) fn frame_index(&self, name: &str) -> Option<usize> {
        self.frames.iter().position(|f| f.name == name)
    }

    pub(crate) fn frame_arg(&self, ast: &Ast, base: usize) -> R<usize> {
        if let AstKind::Name { name, primes: 0 } = &ast.kind
            && let Some(i) = self.frame_index(name)
        {
            return Ok(i);
        }
        let known: Vec<&str> = self.frames.iter().map(|f| f.name.as_str()).collect();
        Err(self.at(
            base,
            ast.span,
            format!("expected a frame name (one of {})", known.join(", ")),
        ))
    }

    /// Adds a frame built by [`Context::frame_of`].
    pub fn push_frame(&mut self, frame: Frame) {
        self.frames.push(frame);
    }

    /// Builds the frame a `[[frame]]` table declares (not yet added).
    pub fn frame_of(&self, f: &RawFrame) -> R<Frame> {
        let name = f.name.get_ref();
        self.valid_name(&f.name, "frame")?;
        if self.frame_index(name).is_some() || self.symbols.get(name).is_some() {
            return Err(self.diag_string(
                &f.name,
                0,
                name.len(),
                format!("`{name}` is already a frame or a symbol"),
            ));
        }
        let mut frame = Frame::inertial(name);
        frame.doc = f.doc.clone();
        if let Some(axes) = &f.axes {
            let a = axes.get_ref();
            if a.len() != 3 || a.iter().any(|s| s.is_empty()) {
                let sp = axes.span();
                return Err(self.diag(
                    sp.start,
                    sp.end,
                    "`axes` must name three axes, such as [\"1\", \"2\", \"3\"]",
                ));
            }
            if let Some(k) = (1..3).find(|&k| a[..k].contains(&a[k])) {
                let sp = axes.span();
                return Err(self.diag(
                    sp.start,
                    sp.end,
                    format!(
                        "`axes` names the axis `{}` twice: the three axes of a frame must differ",
                        a[k]
                    ),
                ));
            }
            frame.axes = [a[0].clone(), a[1].clone(), a[2].clone()];
        }
        match (&f.angular_velocity, &f.parent, &f.rotation) {
            (Some(w), None, None) => {
                let base = self.content_start(w);
                let ast = self.parse_at(w.get_ref(), base)?;
                let AstKind::Vector { items, frame: fr } = &ast.kind else {
                    return Err(self.at(
                        base,
                        ast.span,
                        "the angular velocity must be a vector literal such as [omega_x, omega_y, omega_z]",
                    ));
                };
                if let Some((other, sp)) = fr
                    && other != name
                {
                    return Err(self.at(
                        base,
                        *sp,
                        format!("a frame's angular velocity is given in its own components (`in {name}`)"),
                    ));
                }
                frame.omega = self.three_scalars(items, ast.span, base)?;
            }
            (None, Some(parent), Some(rot)) => {
                let Some(pi) = self.frame_index(parent.get_ref()) else {
                    let p = parent.get_ref();
                    return Err(self.diag_string(
                        parent,
                        0,
                        p.len(),
                        format!("unknown parent frame `{p}` (declare it first)"),
                    ));
                };
                let base = self.content_start(rot);
                let parent_frame = &self.frames[pi];
                let bad = || {
                    format!(
                        "a rotation is written axis(angle), such as {}(phi)",
                        parent_frame.axes[2]
                    )
                };
                // Axes named by numbers (`3(beta)`) are not names the
                // expression parser reads as a function: split them off.
                let text = rot.get_ref();
                let lead = text.len() - text.trim_start().len();
                let numbered = parent_frame.axes.iter().position(|a| {
                    a.starts_with(|c: char| c.is_ascii_digit())
                        && text[lead..].starts_with(&format!("{a}("))
                });
                // Euler parameters: quaternion(e_0, e_1, e_2, e_3).
                let quaternion = super::quaternion::QUATERNION;
                if numbered.is_none()
                    && text[lead..].starts_with(&format!("{quaternion}("))
                    && !parent_frame.axes.iter().any(|a| a == quaternion)
                {
                    let ast = self.parse_at(text, base)?;
                    if let AstKind::Call { args, .. } = &ast.kind {
                        let e = super::quaternion::parameters(self, args, ast.span, base)?;
                        let r = super::quaternion::direction_cosines(&e);
                        // Ω_child = Cᵀ Ω_parent + the axial vector of Cᵀ Ċ.
                        let omega = r.transpose().mul_vec(&parent_frame.omega);
                        let omega = omega.map(|w| super::quaternion::reduce(w, &e));
                        frame.omega = omega.add(&super::quaternion::relative_angular_velocity(&e));
                        frame.parent = Some((parent_frame.name.clone(), r));
                        frame.quaternion = Some(e);
                        return Ok(frame);
                    }
                }
                // The revolute-joint shorthand: about([k_x, k_y, k_z], q).
                let about = super::joints::ABOUT;
                let ast = (numbered.is_none()
                    && text[lead..].starts_with(&format!("{about}("))
                    && !parent_frame.axes.iter().any(|a| a == about))
                .then(|| self.parse_at(text, base))
                .transpose()?;
                if let Some(ast) = &ast
                    && let AstKind::Call { func, args } = &ast.kind
                    && func == about
                {
                    let [axis, arg] = args.as_slice() else {
                        return Err(self.at(
                            base,
                            ast.span,
                            "a hinge is written about([k_x, k_y, k_z], angle): a unit axis in the parent's components and the angle",
                        ));
                    };
                    let q = self.rotation_angle(arg, base)?;
                    let (r, k) = super::joints::hinge(self, axis, q, base)?;
                    // Ω_child = Rᵀ Ω_parent + q̇ k (R k = k).
                    let mut omega = r.transpose().mul_vec(&parent_frame.omega);
                    if let Some(qd) = q.derivative() {
                        omega = omega.add(&k.scale(&Poly::atom(qd)));
                    }
                    frame.omega = omega;
                    frame.parent = Some((parent_frame.name.clone(), r));
                    return Ok(frame);
                }
                let (k, arg, base) = if let Some(k) = numbered {
                    let off = lead + parent_frame.axes[k].len();
                    let arg = self.parse_at(&text[off..], base + off)?;
                    (k, arg, base + off)
                } else {
                    let ast = self.parse_at(text, base)?;
                    let AstKind::Call { func, args } = &ast.kind else {
                        return Err(self.at(base, ast.span, bad()));
                    };
                    let Some(k) = parent_frame.axes.iter().position(|a| a == func) else {
                        return Err(self.at(
                            base,
                            ast.span,
                            format!(
                                "`{func}` is not an axis of frame {}; {}",
                                parent_frame.name,
                                bad()
                            ),
                        ));
                    };
                    let [arg] = args.as_slice() else {
                        return Err(self.at(base, ast.span, bad()));
                    };
                    (k, arg.clone(), base)
                };
                let q = self.rotation_angle(&arg, base)?;
                let r = Mat3::rotation(k, q);
                // Ω_child = Rᵀ Ω_parent + q̇ e_k (e_k is shared by parent and child).
                let mut omega = r.transpose().mul_vec(&parent_frame.omega);
                if let Some(qd) = q.derivative() {
                    omega.0[k] = &omega.0[k] + &Poly::atom(qd);
                }
                frame.omega = omega;
                frame.parent = Some((parent_frame.name.clone(), r));
            }
            _ => {
                let n = f.name.get_ref().len();
                return Err(self.diag_string(
                    &f.name,
                    0,
                    n,
                    "a frame needs either `angular_velocity` or both `parent` and `rotation`",
                ));
            }
        }
        Ok(frame)
    }

    /// The matrix taking components in frame `i` to its root frame, and the root.
    pub(crate) fn to_root(&self, mut i: usize) -> (usize, Mat3) {
        let mut r = Mat3::identity();
        while let Some((p, m)) = &self.frames[i].parent {
            r = m.mul(&r);
            i = self.frame_index(p).expect("parent exists");
        }
        (i, r)
    }

    /// When one frame is an ancestor of the other, turns `v` one rotation
    /// at a time (vector products only, no matrix products).
    pub(crate) fn along_chain(&self, mut v: Vec3, from: usize, to: usize) -> Option<Vec3> {
        let rot = |i: usize| &self.frames[i].parent.as_ref().expect("not a root").1;
        let ancestors = |mut i: usize| {
            let mut v = vec![i];
            while let Some((p, _)) = &self.frames[i].parent {
                i = self.frame_index(p).expect("parent exists");
                v.push(i);
            }
            v
        };
        let up = ancestors(from);
        if let Some(pos) = up.iter().position(|&i| i == to) {
            for &i in &up[..pos] {
                v = rot(i).mul_vec(&v);
            }
            return Some(v);
        }
        let down = ancestors(to);
        let pos = down.iter().position(|&i| i == from)?;
        for &i in down[..pos].iter().rev() {
            v = rot(i).transpose().mul_vec(&v);
        }
        Some(v)
    }

    /// The angle of a frame's rotation: a declared symbol (`x(theta)`,
    /// `about([…], delta)`), located at `base` in the file.
    fn rotation_angle(&self, arg: &Ast, base: usize) -> R<Atom> {
        let AstKind::Name { name: q, primes: 0 } = &arg.kind else {
            return Err(self.at(
                base,
                arg.span,
                "the rotation angle must be a declared symbol",
            ));
        };
        self.symbols
            .atom(q, 0, arg.span)
            .map_err(|e| self.at(base, e.span, e.message))
    }

    pub fn axes_of(&self, v: &Value) -> [String; 3] {
        match v {
            Value::Vector(_, f) => self.frames[self.frame_index(f).expect("frame exists")]
                .axes
                .clone(),
            _ => ["x".into(), "y".into(), "z".into()],
        }
    }

    pub(super) fn default_frame(&self) -> Option<&str> {
        match self.frames.len() {
            1 => Some("N"),
            2 => Some(&self.frames[1].name),
            _ => None,
        }
    }

    pub(crate) fn same_frame(&self, base: usize, span: Span, a: &str, b: &str) -> R<()> {
        if a == b {
            Ok(())
        } else {
            Err(self.at(
                base,
                span,
                format!(
                    "vectors in different frames ({a} and {b}); convert one with express(v, {a})"
                ),
            ))
        }
    }
}
