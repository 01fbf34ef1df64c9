//! The hands on a steering wheel: a load path from the floor through the steering column, the
//! wheel, the forearms and the upper arms to the shoulders — the bench's own form of an upper-body
//! support, two arm segments and a compliant column where the diagnosis's candidate has one arms
//! mass gripping the base.

use super::structure::heaviest_body;
use super::*;

/// Plants the hands on a wheel with strength `u` (the shoulder's stiffness on the upper arms).
///
/// The arms are part of the base model's upper torso (two arms are about a tenth of body mass by
/// segment tables), so they are split off it: upper arms (half to three fifths of the arms) hang on
/// the shoulders, 2–10 Hz on their own mass as `u` rises (ζ 0.2–0.5); the forearms and hands hang
/// on the elbows, 6–14 Hz (ζ 0.3), and grip the rim through palm tissue, 15–40 Hz (ζ 0.2–0.4);
/// the wheel and the column top, 2–5 kg, rest on the column's bending stiffness, 25–45 Hz
/// (ζ 0.03–0.1, a lightly damped steel structure), on the floor.
pub(super) fn plant(u: f64, rng: &mut ChaCha8Rng, model: &mut Chain) -> Result<String> {
    let (ti, tm) = heaviest_body(model);
    let ma = uniform(rng, 5.0, 9.0).min(0.3 * tm);
    let upper = uniform(rng, 0.5, 0.6);
    let (mu, mf) = (upper * ma, (1.0 - upper) * ma);
    model.masses[ti].m = tm - ma;
    let mw = uniform(rng, 2.0, 5.0);
    let (fs, fe, fg, fc) = (
        2.0 + 8.0 * u,
        uniform(rng, 6.0, 14.0),
        uniform(rng, 15.0, 40.0),
        uniform(rng, 25.0, 45.0),
    );
    let (zs, zg, zc) = (
        uniform(rng, 0.2, 0.5),
        uniform(rng, 0.2, 0.4),
        uniform(rng, 0.03, 0.1),
    );
    let j = model.masses.len();
    for (name, m) in [
        ("truth-upper-arms", mu),
        ("truth-forearms", mf),
        ("truth-wheel", mw),
    ] {
        model.masses.push(Mass {
            name: name.into(),
            m,
            role: Role::Handle,
        });
    }
    let (t, ua, fa, w) = (
        Node::Mass(ti),
        Node::Mass(j),
        Node::Mass(j + 1),
        Node::Mass(j + 2),
    );
    let hand = Role::Handle;
    model.links.extend([
        tuned("truth-shoulder", (t, ua), mu, fs, zs, hand),
        tuned("truth-elbow", (ua, fa), mf, fe, 0.3, hand),
        tuned("truth-grip", (fa, w), mf, fg, zg, hand),
        tuned("truth-column", (w, Node::Base), mw, fc, zc, hand),
    ]);
    Ok(format!(
        "hands on a wheel: arms {ma:.1} kg off {} (upper {mu:.1} kg on a {fs:.1} Hz shoulder, ζ {zs:.2}; forearms {mf:.1} kg on a {fe:.1} Hz elbow, grip {fg:.1} Hz, ζ {zg:.2}), wheel {mw:.1} kg on a {fc:.1} Hz column (ζ {zc:.3})",
        model.masses[ti].name
    ))
}
