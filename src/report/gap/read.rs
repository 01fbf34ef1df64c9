//! Reading a diagnosis back from the JSON `wbv gap --json` printed: plain structures rebuilt field
//! by field into a [`Diagnosis`].

use super::*;

/// A number that may be `null` (a NaN when it was written).
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(transparent)]
struct Num(Option<f64>);

impl Num {
    fn get(self) -> f64 {
        self.0.unwrap_or(f64::NAN)
    }
}

#[derive(Debug, Deserialize)]
struct CellIn {
    path: String,
    band_hz: Num,
    gap_db: Num,
    phase_deg: Num,
    coherence: Num,
    sigma_db: Num,
    trusted: bool,
}

#[derive(Debug, Deserialize)]
struct WeightedIn {
    aw_seat_meas: Num,
    aw_seat_model: Num,
    aw_gap_percent: Num,
    seat_meas: Num,
    seat_model: Num,
    driving_bands: Vec<(Num, Num)>,
}

#[derive(Debug, Deserialize)]
struct StageIn {
    chi2_red: Num,
    gap_db_rms: Num,
    phase_deg_rms: Num,
    weighted: WeightedIn,
    cells: Vec<CellIn>,
}

#[derive(Debug, Deserialize)]
struct EstimateIn {
    name: String,
    value: Num,
    sigma: Num,
    change_percent: Option<f64>,
    at_bound: bool,
}

#[derive(Debug, Deserialize)]
struct RankedIn {
    id: String,
    params: Vec<EstimateIn>,
    train_chi2_red: Num,
    delta_bic: Num,
    delta_bic_all: Num,
    probability: Num,
    fraction_closed: Num,
    check: StageIn,
    aw_change_percent: Num,
    seat_change_points: Num,
    band_gap_change_db: Num,
}

#[derive(Debug, Deserialize)]
struct RunIn {
    source: String,
    role: String,
    base_rms: Num,
    peak_hz: Option<f64>,
    gap_db_rms: Vec<(String, Num)>,
}

#[derive(Debug, Deserialize)]
struct CoverageIn {
    path: String,
    judged_hz: Vec<f64>,
    not_judged_hz: Vec<f64>,
}

#[derive(Debug, Deserialize)]
struct DiagnosisIn {
    verdict: String,
    named: Vec<String>,
    bands: Vec<CoverageIn>,
    verdict_text: String,
    warnings: Vec<String>,
    runs: Vec<RunIn>,
    peak_shift_percent_per_doubling: Option<f64>,
    gap_map: Vec<CellIn>,
    classification: Vec<String>,
    nominal: StageIn,
    null: RankedIn,
    candidates: Vec<RankedIn>,
    second: Option<RankedIn>,
    separating_measurement: Option<String>,
    /// Absent from files written before the distortion trend existed.
    #[serde(default)]
    distortion: Option<DistortionIn>,
    /// Absent from files written before the calibration check existed.
    #[serde(default)]
    channel_errors: Vec<crate::diagnosis::ChannelError>,
}

#[derive(Debug, Deserialize)]
struct DistortionIn {
    magnitudes: (Num, Num),
    paths: Vec<PathDistortionIn>,
    site: Option<crate::diagnosis::distortion::Site>,
}

#[derive(Debug, Deserialize)]
struct PathDistortionIn {
    path: String,
    rise_db: Num,
    exponent: Num,
    monotone: bool,
}

/// Rebuilds a [`Diagnosis`] from its JSON; `file` names the source in errors.
struct Rebuild<'a> {
    file: &'a Path,
}

impl Rebuild<'_> {
    /// The diagnosis's own name of path `name` (`base-seat`, …).
    fn path(&self, name: &str) -> Result<&'static str> {
        crate::diagnosis::measure::Path::ALL
            .iter()
            .map(|p| p.name())
            .find(|p| *p == name)
            .ok_or_else(|| {
                Error::data(
                    self.file,
                    None,
                    format!("unknown gap path `{name}`: not written by `wbv gap --json`"),
                )
            })
    }

    fn cell(&self, c: CellIn) -> Result<BandCell> {
        Ok(BandCell {
            path: self.path(&c.path)?,
            band_hz: c.band_hz.get(),
            gap_db: c.gap_db.get(),
            phase_deg: c.phase_deg.get(),
            coherence: c.coherence.get(),
            sigma_db: c.sigma_db.get(),
            trusted: c.trusted,
        })
    }

    fn cells(&self, c: Vec<CellIn>) -> Result<Vec<BandCell>> {
        c.into_iter().map(|c| self.cell(c)).collect()
    }

    fn stage(&self, s: StageIn) -> Result<Stage> {
        let w = s.weighted;
        Ok(Stage {
            chi2_red: s.chi2_red.get(),
            gap_db_rms: s.gap_db_rms.get(),
            phase_deg_rms: s.phase_deg_rms.get(),
            weighted: Weighted {
                aw_seat_meas: w.aw_seat_meas.get(),
                aw_seat_model: w.aw_seat_model.get(),
                aw_gap_percent: w.aw_gap_percent.get(),
                seat_meas: w.seat_meas.get(),
                seat_model: w.seat_model.get(),
                driving_bands: w
                    .driving_bands
                    .into_iter()
                    .map(|(b, s)| (b.get(), s.get()))
                    .collect(),
            },
            cells: self.cells(s.cells)?,
        })
    }

    fn ranked(&self, r: RankedIn) -> Result<Ranked> {
        Ok(Ranked {
            id: r.id,
            params: r
                .params
                .into_iter()
                .map(|p| Estimate {
                    name: p.name,
                    value: p.value.get(),
                    sigma: p.sigma.get(),
                    change_percent: p.change_percent,
                    at_bound: p.at_bound,
                })
                .collect(),
            train_chi2_red: r.train_chi2_red.get(),
            delta_bic: r.delta_bic.get(),
            delta_bic_all: r.delta_bic_all.get(),
            probability: r.probability.get(),
            fraction_closed: r.fraction_closed.get(),
            check: self.stage(r.check)?,
            aw_change_percent: r.aw_change_percent.get(),
            seat_change_points: r.seat_change_points.get(),
            band_gap_change_db: r.band_gap_change_db.get(),
        })
    }

    fn diagnosis(&self, d: DiagnosisIn) -> Result<Diagnosis> {
        let runs = d
            .runs
            .into_iter()
            .map(|r| {
                Ok(RunSummary {
                    source: r.source,
                    role: match r.role.as_str() {
                        "train" => "train",
                        "check" => "check",
                        other => {
                            return Err(Error::data(
                                self.file,
                                None,
                                format!("run role `{other}`: expected train or check"),
                            ));
                        }
                    },
                    base_rms: r.base_rms.get(),
                    peak_hz: r.peak_hz,
                    gap_db_rms: r
                        .gap_db_rms
                        .into_iter()
                        .map(|(p, g)| Ok((self.path(&p)?, g.get())))
                        .collect::<Result<_>>()?,
                })
            })
            .collect::<Result<_>>()?;
        Ok(Diagnosis {
            channel_errors: d.channel_errors,
            verdict: d.verdict,
            named: d.named,
            bands: d
                .bands
                .into_iter()
                .map(|b| {
                    Ok(BandCoverage {
                        path: self.path(&b.path)?,
                        judged_hz: b.judged_hz,
                        not_judged_hz: b.not_judged_hz,
                    })
                })
                .collect::<Result<_>>()?,
            verdict_text: d.verdict_text,
            warnings: d.warnings,
            runs,
            peak_shift_percent_per_doubling: d.peak_shift_percent_per_doubling,
            distortion: d
                .distortion
                .map(|x| {
                    Ok(crate::diagnosis::distortion::Distortion {
                        magnitudes: (x.magnitudes.0.get(), x.magnitudes.1.get()),
                        paths: x
                            .paths
                            .into_iter()
                            .map(|p| {
                                Ok(crate::diagnosis::distortion::PathDistortion {
                                    path: self.path(&p.path)?,
                                    rise_db: p.rise_db.get(),
                                    exponent: p.exponent.get(),
                                    monotone: p.monotone,
                                })
                            })
                            .collect::<Result<_>>()?,
                        site: x.site,
                    })
                })
                .transpose()?,
            gap_map: self.cells(d.gap_map)?,
            classification: d.classification,
            nominal: self.stage(d.nominal)?,
            null: self.ranked(d.null)?,
            candidates: d
                .candidates
                .into_iter()
                .map(|r| self.ranked(r))
                .collect::<Result<_>>()?,
            second: d.second.map(|r| self.ranked(r)).transpose()?,
            separating_measurement: d.separating_measurement,
        })
    }
}

/// Reads a diagnosis from the JSON `wbv gap --json` printed into `file`.
pub fn read(file: &Path) -> Result<Diagnosis> {
    let text = std::fs::read_to_string(file).map_err(|e| Error::io(file, e))?;
    let d: DiagnosisIn = serde_json::from_str(&text).map_err(|e| {
        Error::data(
            file,
            Some(e.line()),
            format!("not the JSON of `wbv gap --json` ({e})"),
        )
    })?;
    Rebuild { file }.diagnosis(d)
}
