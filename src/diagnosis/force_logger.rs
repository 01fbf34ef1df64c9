//! Which logger records the seat-pan force plate, inferred from the data when the loggers are not
//! stated (docs/gap.md §5, acquisition timing). A plate is wired to the occupant's logger in most
//! rigs and to the base's (the shaker controller's, the vehicle's) in the rest. A trigger offset
//! between the loggers then lags every path from the base to a transducer of the late logger by
//! the same phase −2πf·τ: seat and head but not the force when the plate is on the base's logger,
//! which also puts the slope +2πf·τ on the apparent mass F/a_seat. The two groupings predict
//! different phases on the force paths, so a constant offset fitted under each tells them apart.

use super::acquisition::Loggers;
use super::candidate::{self, Retiming};
use super::evidence::Counts;
use super::fitting::{Base, Fitted, fit_candidate};
use super::measure::RunSpectra;
use super::thresholds::{ACCEPT_DELTA_BIC, GAP_CHI2, IDENTIFIABLE_MARGIN};
use crate::error::Result;
use crate::model::Model;

/// The loggers to diagnose with: `assumed` unless a constant offset between the loggers fits the
/// training runs `train` better with the force plate on the base's logger — detected against the
/// `null` re-fit there (ΔBIC ≤ [`ACCEPT_DELTA_BIC`], in sample) and ahead of the same offset
/// with the plate on the occupant's logger by [`IDENTIFIABLE_MARGIN`] (both have one parameter,
/// so ΔBIC is Δχ²), and leaving the training runs' reduced χ² within [`GAP_CHI2`] (the timing is
/// the whole gap). Without a timing effect the offset fits near zero under both and nothing
/// changes. Stated loggers and runs without a force channel are returned as they are. `n` holds
/// the training runs' residual count.
pub(super) fn infer(
    model: &Model,
    assumed: &Loggers,
    train: &[RunSpectra],
    (null, n): (&Fitted, Counts),
    force_measured: bool,
) -> Result<Loggers> {
    if assumed.stated() || !force_measured {
        return Ok(assumed.clone());
    }
    let Some(offset) = candidate::with(|c| c.retiming == Some(Retiming::Offset)) else {
        return Ok(assumed.clone());
    };
    let offset = [offset];
    let on_base = Loggers::force_on_base(0.0);
    let fit =
        |l: &Loggers| fit_candidate(&Base::of(model, l.off_base()), &offset, train, &null.fit.u);
    let (late, early) = (fit(assumed)?, fit(&on_base)?);
    let n = n.train;
    let detected = early.fit.cost - null.fit.cost + n.ln() <= ACCEPT_DELTA_BIC;
    let ahead = late.fit.cost - early.fit.cost >= IDENTIFIABLE_MARGIN;
    // A logger's timing is all the gap there is: with another effect in the runs (a structure,
    // one channel's sensor), a sub-millisecond lag on seat and head also buys χ² by bending the
    // phase, and blind lab cases with one time base were read as two loggers that way.
    let explains = early.fit.cost / n <= GAP_CHI2;
    if !(detected && ahead && explains) {
        return Ok(assumed.clone());
    }
    let lag_s = early.variant.chain.seat.delay_s;
    Ok(Loggers::force_on_base(lag_s))
}
