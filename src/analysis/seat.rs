//! Seat effective amplitude transmissibility (ISO 10326-1:2016 10.2.2; paper 000 eq. 14):
//! SEAT % = 100 · a_w(seat) / a_w(base), both weighted with the same weighting. Below 100 % the
//! seat attenuates the weighted vibration.

/// SEAT in percent from the weighted r.m.s. of seat and base (m/s²); `None` if the base is still.
pub fn seat_percent(a_w_seat: f64, a_w_base: f64) -> Option<f64> {
    (a_w_base > 0.0).then(|| 100.0 * a_w_seat / a_w_base)
}
