"""Bad input raises `wbv.WbvError` (a `ValueError`) with the command's message; nothing is
written and nothing half-done is returned."""

import numpy as np
import pytest

import wbv

FS = 200.0
GOOD = np.sin(np.arange(int(12 * FS)) / FS * 2 * np.pi * 4.0)


def test_the_error_is_a_value_error():
    assert issubclass(wbv.WbvError, ValueError)


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: wbv.analyze({"a_seat_z": np.where(np.arange(GOOD.size) == 99, np.nan, GOOD)}, FS),
         "sample 100 (index 99) is not finite"),
        (lambda: wbv.analyze({"a_seat_z": np.full(GOOD.size, np.inf)}, FS), "not finite"),
        (lambda: wbv.analyze({"seat": GOOD}, FS), "`seat` is not a channel name"),
        (lambda: wbv.analyze({}, FS), "no column is named"),
        (lambda: wbv.analyze({"a_seat_z": GOOD}, -200.0), "fs: -200 Hz"),
        (lambda: wbv.analyze({"a_seat_z": GOOD}, float("nan")), "fs: "),
        (lambda: wbv.analyze({"a_seat_z": GOOD[:100]}, FS), "at least 10 s"),
        (lambda: wbv.analyze({"a_seat_z": GOOD, "a_base_z": GOOD[:-1]}, FS), "a_base_z"),
        (lambda: wbv.analyze({"a_seat_z": GOOD.reshape(2, -1)}, FS), "1-D array"),
        (lambda: wbv.analyze({"a_seat_z": ["a"] * GOOD.size}, FS), "array of numbers"),
        (lambda: wbv.analyze({"a_seat_z": GOOD}, FS, units="furlong"), "units: `furlong`"),
        (lambda: wbv.analyze({"a_seat_z": GOOD * 1e5}, FS), "beyond"),
        (lambda: wbv.simulate("no-such-model", "bell-214", 1, 1), "`no-such-model` is neither"),
        (lambda: wbv.simulate("reference", "no-such-excitation", 1, 1), "neither a built-in"),
        (lambda: wbv.simulate("reference", "bell-214", -1, 1), "duration: -1 s"),
        (lambda: wbv.simulate("reference", "bell-214", 1, 1, dt=-0.001), "dt: "),
        (lambda: wbv.simulate("reference", "bell-214", 1, -1), "seed: -1"),
        (lambda: wbv.simulate("reference", "bell-214", 1, 1, integrator="euler"), "euler"),
        (lambda: wbv.simulate("reference", "random", 1, 1), "rms: required"),
        (lambda: wbv.simulate("reference", "bell-214", 1, 1, rms=1.0), "rms: does not apply"),
        (lambda: wbv.simulate("reference", "random", 1, 1, rmss=1.0), "rmss: not an excitation"),
        (lambda: wbv.frf("reference", [1.0, np.nan]), "frequency 2 is NaN"),
        (lambda: wbv.frf("reference", []), "no frequencies"),
        (lambda: wbv.modes("nope"), "`nope` is neither"),
        (lambda: wbv.sweep("reference", {"link.nope.k": "1:2:3"}), "link.nope.k"),
        (lambda: wbv.sweep("reference", {"link.cushion.k": [1.0, np.inf]}), "value 2 is inf"),
        (lambda: wbv.sweep("reference", {"link.cushion.k": "1:2"}), "from:to:count"),
        (lambda: wbv.sweep("reference", {"link.cushion.k": "1:2:3"}, time_domain=True),
         "time_domain: "),
        (lambda: wbv.sweep("reference", {"link.cushion.k": "1:2:3"}, rms=1.0), "give an excitation"),
        (lambda: wbv.gap([{"a_seat_z": GOOD}], {"a_seat_z": GOOD}, "reference", fs=FS),
         "needs channels a_base_z and a_seat_z"),
        (lambda: wbv.gap([{"a_base_z": GOOD, "a_seat_z": GOOD}], {"a_base_z": GOOD, "a_seat_z": GOOD},
                         "reference"), "fs: the sample rate"),
        (lambda: wbv.gap([], {"a_base_z": GOOD, "a_seat_z": GOOD}, "reference", fs=FS,
                         loggers=["nonsense"]), "loggers: "),
        (lambda: wbv.seat_test("scissor-seat", "iso7096-em99"), "`iso7096-em99` is not an input"),
        (lambda: wbv.seat_test("scissor-seat", "iso7096-em3", occupant="child"), "occupant: "),
        (lambda: wbv.seat_test("scissor-seat", "iso7096-em3", duration=-600), "duration: "),
        (lambda: wbv.seat_test("scissor-seat", "iso7096-em3", seat_limit=-1), "seat_limit: "),
        (lambda: wbv.seat_test(None, "iso7096-em3"), "model: required"),
        (lambda: wbv.seat_test(None, "iso7096-em3", runs=[{"a_base_z": GOOD, "a_seat_z": GOOD}],
                               fs=FS), "ISO 10326-1 10.2.1 needs at least 3 runs"),
        (lambda: wbv.seat_test(None, "iso7096-em3", runs=[{"a_seat_z": GOOD}] * 3, fs=FS),
         "a_base_z"),
        (lambda: wbv.seat_test(None, "iso7096-em3", runs=[{"a_base_z": GOOD, "a_seat_z": GOOD}] * 3,
                               fs=-FS), "fs: "),
        (lambda: wbv.exposure([({"a_seat_z": GOOD}, 30.0)], fs=FS), "hours"),
        (lambda: wbv.exposure([({"a_seat_z": GOOD}, -1.0)], fs=FS), "operations[0]: -1 h; expected 0 < hours"),
        (lambda: wbv.exposure([({"a_seat_z": GOOD * np.nan}, 2.0)], fs=FS), "not finite"),
        (lambda: wbv.exposure([], fs=FS), "operation"),
        (lambda: wbv.exposure([({"a_seat_z": GOOD}, 2.0)], fs=FS, spine_years=0), "spine_years: "),
        (lambda: wbv.exposure([({"a_seat_z": GOOD}, 2.0)], fs=FS, spine_sex="x"), "spine_sex: "),
        (lambda: wbv.seat_test("scissor-seat", "iso7096-em3,iso7096-em3"), "classes: `iso7096-em3` given twice"),
        (lambda: wbv.seat_test("scissor-seat", ["iso7096-em3"], contact_limit=-1), "contact_limit: "),
        (lambda: wbv.seat_test(None, ["iso7096-em3", "iso7096-em6"], fs=FS,
                               runs=[{"a_base_z": GOOD, "a_seat_z": GOOD}] * 3), "classes: 2 classes"),
        (lambda: wbv.exposure([({"a_seat_z": GOOD}, -FS, 2.0)]), "fs: "),
        # Complex samples are refused, not silently cut to their real part.
        (lambda: wbv.analyze({"a_seat_z": GOOD * (1 + 1j)}, FS), "complex samples"),
        (lambda: wbv.exposure([({"a_seat_z": GOOD + 0j}, FS, 2.0)]), "complex samples"),
    ],
)
def test_bad_input_raises_the_commands_message(call, message):
    with pytest.raises(wbv.WbvError) as e:
        call()
    assert message in str(e.value)


def test_nothing_is_written_on_bad_input(tmp_path):
    with pytest.raises(wbv.WbvError):
        wbv.simulate("reference", "bell-214", -1, 1, record=tmp_path / "run")
    assert not (tmp_path / "run").exists() or not any((tmp_path / "run").iterdir())


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: wbv.analyze({"a_seat_z": GOOD}, "1000"), "fs must be a number (got str)"),
        (lambda: wbv.seat_test(None, "iso7096-em3", runs=[{"a_base_z": GOOD, "a_seat_z": GOOD}] * 3,
                               fs="200"), "fs must be a number (got str)"),
        (lambda: wbv.seat_test("scissor-seat", "iso7096-em3", seat_limit="1.0"),
         "seat_limit must be a number (got str)"),
        (lambda: wbv.exposure([({"a_seat_z": GOOD}, "2")], fs=FS),
         "operations[0].hours must be a number (got str)"),
        (lambda: wbv.exposure([({"a_seat_z": GOOD}, FS, 2.0), ({"a_seat_z": GOOD}, True, 2.0)]),
         "operations[1].fs must be a number (got bool)"),
        (lambda: wbv.gap([], {"a_base_z": GOOD, "a_seat_z": GOOD}, "reference", fs=[FS]),
         "fs must be a number (got list)"),
    ],
)
def test_a_value_of_the_wrong_type_is_a_type_error_naming_the_parameter(call, message):
    with pytest.raises(TypeError) as e:
        call()
    assert str(e.value) == message


def test_complex_samples_raise_no_numpy_warning():
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(wbv.WbvError):
            wbv.analyze({"a_seat_z": GOOD.astype(np.complex128)}, FS)


def test_help_shows_the_defaults_and_units():
    import pydoc

    import inspect

    text = pydoc.render_doc(wbv.seat_test, renderer=pydoc.plaintext)
    assert "Ellipsis" not in text and "=..." not in text, text[:400]
    # The signature help() prints first carries the real defaults.
    params = inspect.signature(wbv.seat_test).parameters
    assert params["duration"].default == 600.0 and params["dt"].default == 0.001, params
    assert params["classes"].default is None and params["damping"].default is True
    for default in ["classes=None", "seat_limit=None", "contact_limit=None", "duration=600.0",
                    "dt=0.001", "seed=1", "damping=True"]:
        assert default in text, default
    for unit in ["m/s²", " Hz", " s each", "m/s^1.75", "per 10 min"]:
        assert unit in text, unit
    text = pydoc.render_doc(wbv.exposure, renderer=pydoc.plaintext)
    assert "fs=None" in text and "(samples, fs, hours)" in text and "1.1 ×" in text
