//! The bench's summary: rows by family, form, nuisance and strength tier, the confusion of
//! verdicts, the acceptance rule of issue 15, and its text and Markdown tables.

use super::*;
use crate::numeric::median;

/// One row of a summary table.
#[derive(Debug, Clone, Serialize)]
pub struct Row {
    /// Grouping (`family`, `form`, `nuisance`, `tier`).
    pub group: String,
    /// Row key.
    pub key: String,
    /// Cases in the row.
    pub cases: usize,
    /// Top-1 rate.
    pub top1: f64,
    /// Top-2 rate.
    pub top2: f64,
    /// Cases above the detectability threshold.
    pub detectable: usize,
    /// Top-1 rate above the detectability threshold.
    pub top1_detectable: Option<f64>,
    /// Median fraction closed by the truth's family (cases where it was fitted).
    pub median_closed: Option<f64>,
    /// Cases that ended in an error.
    pub errors: usize,
    /// Median |seat a_w gap| on the check run, %: re-fitted base model, then with the named
    /// effect(s) — how close the answer brings the ISO figure.
    pub median_aw_gap: Option<(f64, f64)>,
    /// The same for the SEAT gap, percentage points.
    pub median_seat_gap: Option<(f64, f64)>,
}

/// The bench summary.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// Cases.
    pub cases: usize,
    /// Master seed.
    pub seed: u64,
    /// Wall time of the whole bench, s.
    pub wall_s: f64,
    /// Detectability threshold.
    pub detectable_threshold: f64,
    /// `none` false-positive rate on no-effect cases (verdict other than `none`, errors included).
    pub none_false_positive_rate: Option<f64>,
    /// No-effect cases.
    pub null_cases: usize,
    /// Cases that ended in an error.
    pub errors: usize,
    /// Rows by family, form, nuisance and tier.
    pub rows: Vec<Row>,
    /// Confusion counts (truth family → verdict, count).
    pub confusion: Vec<(String, String, usize)>,
    /// Median diagnosis wall time per case, s.
    pub median_diagnosis_s: f64,
    /// How the check run's ISO figures move when an effect is named.
    pub iso_toward: IsoToward,
    /// Support-path cases named a support path: (planted form, named candidate, count), and how
    /// many of them name the planted place ([`Form::places`]).
    pub support_places: (Vec<(String, String, usize)>, usize),
}

/// Of the cases whose verdict names an effect: how many bring the check run's seat a_w and SEAT
/// toward the measurement (neither gap grows by more than [`TIE`] against the re-fitted model),
/// and the median gaps that remain.
#[derive(Debug, Clone, Serialize)]
pub struct IsoToward {
    /// Cases naming an effect.
    pub named: usize,
    /// Of those, cases moving both figures toward the measurement against the re-fitted base
    /// model (the verdict's own comparison, `verdict::shortfall`).
    pub toward: usize,
    /// Of those, cases moving both figures toward the measurement against the model as given
    /// (the nominal model: what the user had before the diagnosis).
    pub toward_nominal: usize,
    /// Of those, cases where neither gap grows against the re-fitted model by more than [`TIE`] or
    /// twice the standard error the named model's fitted parameters give the figure (the verdict's
    /// own allowance for the fit's scatter, `verdict::shortfall`).
    pub within_sigma: usize,
    /// Of those, cases where neither gap grows by the diagnosis's own "away" threshold
    /// ([`crate::diagnosis::ISO_AWAY`]: 1 % of a_w, 1 SEAT point, below which a shift is not of
    /// practical size); the rest are the cases the verdict itself flags.
    pub within_practical: usize,
    /// The named verdicts whose effects are all linear.
    pub linear: Kind,
    /// The named verdicts naming an amplitude-dependent effect (their a_w and SEAT are replayed
    /// through the fitted nonlinear model, [`super::IsoGaps::amplitude_dependent`]).
    pub amplitude_dependent: Kind,
    /// Median remaining |a_w gap| with the named effect(s), %.
    pub median_aw_gap_percent: Option<f64>,
    /// Median remaining |SEAT gap| with the named effect(s), points.
    pub median_seat_gap_points: Option<f64>,
}

/// One kind of named effect's cases in [`IsoToward`], against the re-fitted model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Kind {
    /// Cases naming this kind of effect.
    pub cases: usize,
    /// Of those, `toward` ([`IsoToward::toward`]: neither gap grows by more than [`TIE`]).
    pub toward: usize,
    /// Of those, `within_practical` ([`IsoToward::within_practical`]).
    pub within_practical: usize,
}

/// Change of an ISO gap (% or points) read as a tie: the figures' own rounding in the report.
pub const TIE: f64 = 0.1;

fn iso_toward(scores: &[CaseScore]) -> IsoToward {
    let named: Vec<&IsoGaps> = scores
        .iter()
        .filter(|s| !s.named.is_empty())
        .filter_map(|s| s.iso.as_ref())
        .collect();
    toward_of(&named)
}

/// [`IsoToward`] of the ISO gaps of the cases whose verdict names an effect.
fn toward_of(named: &[&IsoGaps]) -> IsoToward {
    // `from`: 0 the nominal model, 1 the re-fitted one; the named model is the third. `tie`: the
    // growth of the a_w (%) and SEAT (points) gaps read as no growth, per case.
    let moves_toward = |g: &IsoGaps, from: usize, (aw, seat): (f64, f64)| {
        g.aw_percent[2].abs() <= g.aw_percent[from].abs() + aw
            && g.seat_points[2].abs() <= g.seat_points[from].abs() + seat
    };
    let within = |from: usize, tie: &dyn Fn(&IsoGaps) -> (f64, f64)| {
        named
            .iter()
            .filter(|g| moves_toward(g, from, tie(g)))
            .count()
    };
    let rounding = |_: &IsoGaps| (TIE, TIE);
    let (toward, within_practical) = (
        within(1, &rounding),
        within(1, &|_| crate::diagnosis::ISO_AWAY),
    );
    let split = |amplitude_dependent: bool| {
        let of: Vec<&&IsoGaps> = (named.iter())
            .filter(|g| g.amplitude_dependent == amplitude_dependent)
            .collect();
        let count = |tie: (f64, f64)| of.iter().filter(|g| moves_toward(g, 1, tie)).count();
        Kind {
            cases: of.len(),
            toward: count((TIE, TIE)),
            within_practical: count(crate::diagnosis::ISO_AWAY),
        }
    };
    let within_sigma = within(1, &|g| {
        let [s_aw, s_seat] = g.sigma.unwrap_or([0.0, 0.0]);
        (TIE.max(2.0 * s_aw), TIE.max(2.0 * s_seat))
    });
    let of = |f: fn(&IsoGaps) -> f64| median(named.iter().map(|g| f(g)).collect());
    IsoToward {
        named: named.len(),
        toward,
        toward_nominal: within(0, &rounding),
        within_sigma,
        within_practical,
        linear: split(false),
        amplitude_dependent: split(true),
        median_aw_gap_percent: of(|g| g.aw_percent[2].abs()),
        median_seat_gap_points: of(|g| g.seat_points[2].abs()),
    }
}

/// The share `k / n`, `None` of nothing.
fn share(k: usize, n: usize) -> Option<f64> {
    (n > 0).then(|| k as f64 / n as f64)
}

fn row(group: &str, key: String, c: &[&CaseScore]) -> Row {
    let n = c.len().max(1) as f64;
    let det: Vec<&&CaseScore> = c
        .iter()
        .filter(|s| s.tier == "medium" || s.tier == "strong")
        .collect();
    Row {
        group: group.into(),
        key,
        cases: c.len(),
        top1: c.iter().filter(|s| s.top1).count() as f64 / n,
        top2: c.iter().filter(|s| s.top2_hit).count() as f64 / n,
        detectable: det.len(),
        top1_detectable: share(det.iter().filter(|s| s.top1).count(), det.len()),
        median_closed: median(c.iter().filter_map(|s| s.fraction_closed).collect()),
        errors: c.iter().filter(|s| s.error.is_some()).count(),
        median_aw_gap: median_pair(c, |g| g.aw_percent),
        median_seat_gap: median_pair(c, |g| g.seat_points),
    }
}

/// Medians of |re-fitted| and |named| of an ISO gap over the cases that have it.
fn median_pair(c: &[&CaseScore], gap: impl Fn(&IsoGaps) -> [f64; 3]) -> Option<(f64, f64)> {
    let g: Vec<[f64; 3]> = c.iter().filter_map(|s| s.iso.as_ref()).map(gap).collect();
    Some((
        median(g.iter().map(|v| v[1].abs()).collect())?,
        median(g.iter().map(|v| v[2].abs()).collect())?,
    ))
}

/// A nuisance row's test of a case.
type Pred = Box<dyn Fn(&CaseScore) -> bool>;

/// The nuisance rows: their names and which cases they hold.
fn nuisances() -> Vec<(String, Pred)> {
    let mut nuisances: Vec<(String, Pred)> = vec![
        (
            "spectrum white".into(),
            Box::new(|s: &CaseScore| s.label.nuisance.spectrum == "white"),
        ),
        (
            "spectrum helicopter".into(),
            Box::new(|s: &CaseScore| s.label.nuisance.spectrum == "helicopter"),
        ),
        (
            "spectrum road".into(),
            Box::new(|s: &CaseScore| s.label.nuisance.spectrum == "road"),
        ),
        (
            "spectrum shaped".into(),
            Box::new(|s: &CaseScore| s.label.nuisance.spectrum == "shaped"),
        ),
        (
            "fs ≤ 256 Hz".into(),
            Box::new(|s: &CaseScore| s.label.nuisance.fs_hz <= 256.0),
        ),
        (
            "fs 500–512 Hz".into(),
            Box::new(|s: &CaseScore| (500.0..=512.0).contains(&s.label.nuisance.fs_hz)),
        ),
        (
            "fs ≥ 1000 Hz".into(),
            Box::new(|s: &CaseScore| s.label.nuisance.fs_hz >= 1000.0),
        ),
        (
            "duration < 120 s".into(),
            Box::new(|s: &CaseScore| s.label.nuisance.duration_s < 120.0),
        ),
        (
            "duration ≥ 120 s".into(),
            Box::new(|s: &CaseScore| s.label.nuisance.duration_s >= 120.0),
        ),
        (
            "noise < 1.5 %".into(),
            Box::new(|s: &CaseScore| s.label.nuisance.noise_percent < 1.5),
        ),
        (
            "noise ≥ 1.5 %".into(),
            Box::new(|s: &CaseScore| s.label.nuisance.noise_percent >= 1.5),
        ),
        (
            "with f_seat_z".into(),
            Box::new(|s: &CaseScore| s.label.nuisance.force),
        ),
        (
            "without f_seat_z".into(),
            Box::new(|s: &CaseScore| !s.label.nuisance.force),
        ),
        (
            "mass error ≥ 7 %".into(),
            Box::new(|s: &CaseScore| s.label.nuisance.mass_error_percent >= 7.0),
        ),
        (
            "two effects".into(),
            Box::new(|s: &CaseScore| s.label.effects.len() > 1),
        ),
    ];
    for f in crate::gap_bench::case::logger::FAULTS {
        nuisances.push((
            format!("logger {f}"),
            Box::new(move |s: &CaseScore| s.label.nuisance.logger_fault == Some(f)),
        ));
    }
    nuisances
}

/// Summarises case scores.
pub fn summary(scores: &[CaseScore], seed: u64, wall_s: f64) -> Summary {
    let mut rows = Vec::new();
    let effect: Vec<&CaseScore> = scores
        .iter()
        .filter(|s| !s.label.effects.is_empty())
        .collect();
    for f in Family::ALL {
        let c: Vec<&CaseScore> = effect
            .iter()
            .copied()
            .filter(|s| s.label.effects[0].family == f)
            .collect();
        if !c.is_empty() {
            rows.push(row("family", f.name().into(), &c));
        }
    }
    for f in Form::ALL {
        let c: Vec<&CaseScore> = effect
            .iter()
            .copied()
            .filter(|s| s.label.effects[0].form == f)
            .collect();
        if !c.is_empty() {
            rows.push(row(
                "form",
                format!("{}/{}", f.family().name(), f.name()),
                &c,
            ));
        }
    }
    rows.extend(backrest_identifiability(&effect));
    let nuisances = nuisances();
    for (k, p) in &nuisances {
        let c: Vec<&CaseScore> = effect.iter().copied().filter(|s| p(s)).collect();
        if !c.is_empty() {
            rows.push(row("nuisance", k.clone(), &c));
        }
    }
    for t in ["weak", "medium", "strong"] {
        let c: Vec<&CaseScore> = effect.iter().copied().filter(|s| s.tier == t).collect();
        if !c.is_empty() {
            rows.push(row("tier", t.into(), &c));
        }
    }
    let nulls: Vec<&CaseScore> = scores
        .iter()
        .filter(|s| s.label.effects.is_empty())
        .collect();
    for (k, p) in &nuisances {
        let c: Vec<&CaseScore> = nulls.iter().copied().filter(|s| p(s)).collect();
        if !c.is_empty() && !k.starts_with("two") {
            rows.push(row("null", k.clone(), &c));
        }
    }
    let mut confusion: Vec<(String, String, usize)> = Vec::new();
    for s in scores {
        let t = s
            .label
            .effects
            .first()
            .map_or("none".to_string(), |e| e.family.name().to_string());
        let v = s
            .named
            .first()
            .and_then(|n| Family::of_verdict(n))
            .map_or(s.verdict.clone(), |f| f.name().to_string());
        match confusion.iter_mut().find(|c| c.0 == t && c.1 == v) {
            Some(c) => c.2 += 1,
            None => confusion.push((t, v, 1)),
        }
    }
    confusion.sort();
    let support_places = support_places(scores);
    Summary {
        cases: scores.len(),
        seed,
        wall_s,
        detectable_threshold: DETECTABLE,
        none_false_positive_rate: share(nulls.iter().filter(|s| !s.top1).count(), nulls.len()),
        null_cases: nulls.len(),
        errors: scores.iter().filter(|s| s.error.is_some()).count(),
        rows,
        confusion,
        median_diagnosis_s: median(scores.iter().map(|s| s.diagnosis_s).collect()).unwrap_or(0.0),
        iso_toward: iso_toward(scores),
        support_places,
    }
}

/// The backrest cases by what their channels allow. Half measure the backrest's vertical force
/// (`f_back_z`), which only a backrest carries. The z-only rest (base, seat, head and seat-pan
/// force) split: where the re-fitted base model already fits the held-out run within the noise
/// (reduced χ² ≤ 1), a backrest is not identifiable from them — masses and stiffnesses within
/// their ±30 % absorb it — and `none` is the answer the data support; elsewhere it is.
fn backrest_identifiability(effect: &[&CaseScore]) -> Vec<Row> {
    let (instrumented, backrest): (Vec<&CaseScore>, Vec<&CaseScore>) = effect
        .iter()
        .copied()
        .filter(|s| s.label.effects[0].form == Form::Backrest)
        .partition(|s| s.label.nuisance.backrest_force);
    let within = |s: &&CaseScore| s.chi2_red.is_some_and(|c| c[0] <= 1.0);
    let (absorbed, seen): (Vec<&CaseScore>, Vec<&CaseScore>) =
        backrest.iter().copied().partition(within);
    [
        ("backrest with f_back_z measured", instrumented),
        ("backrest z-only, null beyond the noise", seen),
        (
            "backrest z-only, null within the noise (not identifiable)",
            absorbed,
        ),
    ]
    .into_iter()
    .filter(|(_, c)| !c.is_empty())
    .map(|(k, c)| row("identifiability", k.into(), &c))
    .collect()
}

/// Where the support-path verdicts put the path: over the cases whose first planted effect is a
/// support path and whose first named effect is one, (form, named id, count) and the count of
/// those naming the planted place.
fn support_places(scores: &[CaseScore]) -> (Vec<(String, String, usize)>, usize) {
    let mut out: Vec<(String, String, usize)> = Vec::new();
    let mut right = 0;
    for s in scores {
        let Some(e) = s.label.effects.first() else {
            continue;
        };
        let (Some(places), Some(n)) = (e.form.places(), s.named.first()) else {
            continue;
        };
        if Family::of_verdict(n) != Some(Family::SupportPath) {
            continue;
        }
        right += usize::from(places.contains(&n.as_str()));
        let key = (e.form.name().to_string(), n.clone());
        match out.iter_mut().find(|c| (&c.0, &c.1) == (&key.0, &key.1)) {
            Some(c) => c.2 += 1,
            None => out.push((key.0, key.1, 1)),
        }
    }
    out.sort();
    (out, right)
}

impl Summary {
    /// The acceptance check of issue 15: per family top-1 ≥ 0.9 above the detectability threshold,
    /// `none` false positives ≤ 0.1, no errors. Returns the failed conditions.
    pub fn failures(&self) -> Vec<String> {
        let mut out = Vec::new();
        for r in self.rows.iter().filter(|r| r.group == "family") {
            if let Some(a) = r.top1_detectable
                && a < 0.9
            {
                out.push(format!(
                    "family {}: top-1 {a:.2} < 0.90 on {} detectable cases",
                    r.key, r.detectable
                ));
            }
        }
        if let Some(fp) = self.none_false_positive_rate
            && fp > 0.1
        {
            out.push(format!("`none` false-positive rate {fp:.2} > 0.10"));
        }
        if self.errors > 0 {
            out.push(format!("{} cases ended in an error", self.errors));
        }
        out
    }

    /// A Markdown table (docs/gap-validation.md's).
    pub fn markdown(&self) -> String {
        let f = |x: Option<f64>| x.map_or("–".to_string(), |v| format!("{v:.2}"));
        let mut out = format!(
            "`wbv gap-bench --cases {} --seed {}`: {} cases ({} without an effect), wall time {:.0} s on this 2-core machine, median diagnosis {:.1} s; detectability threshold {:.1}; `none` false-positive rate {}; {} errors.\n\n",
            self.cases,
            self.seed,
            self.cases,
            self.null_cases,
            self.wall_s,
            self.median_diagnosis_s,
            self.detectable_threshold,
            f(self.none_false_positive_rate),
            self.errors
        );
        let t = &self.iso_toward;
        out += &format!(
            "Named verdicts moving the check run's seat a_w and SEAT toward the measurement (neither gap growing by more than {TIE}) against the model as given: {} of {} ({}); against the re-fitted base model: {} ({}), or {} ({}) where a growth within twice the named model's own standard error (from its fitted parameters' covariance) counts as a tie; neither growing against the re-fitted model by the diagnosis's practical size ({} % a_w, {} SEAT point): {} ({}); median remaining |a_w gap| {} %, |SEAT gap| {} points. Against the re-fitted model by the kind of effect named (growth within {TIE}; within the practical size): linear effects {} of {} ({}; {} ({})); amplitude-dependent effects, whose a_w and SEAT come from a replay of the check run's measured base through the fitted nonlinear model, {} of {} ({}; {} ({})).\n\n",
            t.toward_nominal,
            t.named,
            f(share(t.toward_nominal, t.named)),
            t.toward,
            f(share(t.toward, t.named)),
            t.within_sigma,
            f(share(t.within_sigma, t.named)),
            crate::diagnosis::ISO_AWAY.0,
            crate::diagnosis::ISO_AWAY.1,
            t.within_practical,
            f(share(t.within_practical, t.named)),
            f(t.median_aw_gap_percent),
            f(t.median_seat_gap_points),
            t.linear.toward,
            t.linear.cases,
            f(share(t.linear.toward, t.linear.cases)),
            t.linear.within_practical,
            f(share(t.linear.within_practical, t.linear.cases)),
            t.amplitude_dependent.toward,
            t.amplitude_dependent.cases,
            f(share(
                t.amplitude_dependent.toward,
                t.amplitude_dependent.cases
            )),
            t.amplitude_dependent.within_practical,
            f(share(
                t.amplitude_dependent.within_practical,
                t.amplitude_dependent.cases
            )),
        );
        let pair = |x: Option<(f64, f64)>, d: usize| {
            x.map_or("–".to_string(), |(a, b)| format!("{a:.d$} → {b:.d$}"))
        };
        out += "| group | row | cases | top-1 | top-2 | detectable | top-1 detectable | median closed | median \\|a_w gap\\| % re-fitted → named | median \\|SEAT gap\\| points | errors |\n";
        out += "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        for r in &self.rows {
            out += &format!(
                "| {} | {} | {} | {:.2} | {:.2} | {} | {} | {} | {} | {} | {} |\n",
                r.group,
                r.key,
                r.cases,
                r.top1,
                r.top2,
                r.detectable,
                f(r.top1_detectable),
                f(r.median_closed),
                pair(r.median_aw_gap, 1),
                pair(r.median_seat_gap, 1),
                r.errors
            );
        }
        out
    }

    /// Readable text: the table plus the confusion counts.
    pub fn text(&self) -> String {
        let mut out = self.markdown();
        out += "\nconfusion (first planted family → named family or verdict: count)\n";
        for (t, v, n) in &self.confusion {
            out += &format!("  {t:<14} → {v:<18} {n}\n");
        }
        let (places, right) = &self.support_places;
        let named: usize = places.iter().map(|p| p.2).sum();
        out += &format!(
            "support-path place (planted form → named support path: count): {right} of {named} at the planted place\n"
        );
        for (f, v, n) in places {
            out += &format!("  {f:<14} → {v:<18} {n}\n");
        }
        let fails = self.failures();
        if fails.is_empty() {
            out += "acceptance (issue 15): met\n";
        } else {
            out += &format!("acceptance (issue 15): NOT met — {}\n", fails.join("; "));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gaps(aw: [f64; 3], amplitude_dependent: bool) -> IsoGaps {
        IsoGaps {
            aw_percent: aw,
            seat_points: [0.0; 3],
            sigma: None,
            amplitude_dependent,
        }
    }

    #[test]
    fn toward_counts_each_kind_of_effect_against_the_re_fitted_model() {
        // Gaps nominal, re-fitted, named (% a_w): a linear effect closing, one moving 0.05 away
        // (a tie at the report's rounding) and one moving 0.5 away; an amplitude-dependent effect
        // moving 0.3 away from the re-fit but toward the measurement from the nominal model, and
        // one moving 1.5 away (beyond the practical size of 1 %).
        let named = [
            gaps([4.0, 1.0, 0.2], false),
            gaps([4.0, 0.2, -0.25], false),
            gaps([4.0, 0.2, 0.7], false),
            gaps([4.0, -0.1, -0.4], true),
            gaps([4.0, 0.1, 1.6], true),
        ];
        let refs: Vec<&IsoGaps> = named.iter().collect();
        let t = toward_of(&refs);
        assert_eq!((t.named, t.toward, t.toward_nominal), (5, 2, 5));
        let kind = |cases, toward, within_practical| Kind {
            cases,
            toward,
            within_practical,
        };
        assert_eq!(t.linear, kind(3, 2, 3));
        assert_eq!(t.amplitude_dependent, kind(2, 0, 1));
    }
}
