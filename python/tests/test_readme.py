"""The README's Python examples run as written (read from README.md, so they cannot drift)."""

import pathlib
import re

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]


def python_blocks():
    text = (ROOT / "README.md").read_text()
    section = text[text.index("## Python\n") :]
    section = section[: section.index("\n## ", 1)]
    return re.findall(r"```python\n(.*?)```", section, re.S)


def test_the_comfort_check_in_your_own_test_passes():
    intro, check = python_blocks()
    scope = {}
    exec(compile(check, "README.md (comfort check)", "exec"), scope)
    tests = [f for name, f in scope.items() if name.startswith("test_")]
    assert len(tests) == 1
    tests[0]()


def test_the_iso_table_of_your_own_samples_runs(tmp_path, monkeypatch, capsys):
    intro, _ = python_blocks()
    # "your samples": a logger's CSV with a time column and a seat column, 60 s at 1 kHz.
    t = np.arange(60_000) / 1000.0
    seat = 0.5 * np.sin(2 * np.pi * 4.0 * t) + 0.1 * np.sin(2 * np.pi * 11.0 * t)
    np.savetxt(tmp_path / "seat.csv", np.column_stack([t, seat]), delimiter=",",
               header="t_s,a_seat_z", comments="")
    monkeypatch.chdir(tmp_path)
    exec(compile(intro, "README.md (Python)", "exec"), {})
    out = capsys.readouterr().out.splitlines()
    assert out[0].split()[:2] == ["channel", "a_w"]
    name, a_w = out[1].split()[:2]
    # A 4 Hz and an 11 Hz sine: a_w = sqrt(Σ (W_k(f) A/√2)²); W_k(4 Hz) ≈ 1.0, W_k(11 Hz) ≈ 0.95
    # (ISO 2631-1 Table 3, 4 Hz: 1.036 at the band, 10 Hz: 0.988, 12.5 Hz: 0.902): about 0.36.
    assert name == "a_seat_z" and 0.33 < float(a_w) < 0.40
