"""Writes measurement files with independent tools (scipy, soundfile, pyuff, the PyPI mcap writers,
Python's csv module in the styles spreadsheets export, numpy.savetxt) and a manifest of what each
holds, for tests/input_fixtures.rs (and the files tests/first_hour.rs runs `wbv` on).

Usage: gen.py OUTDIR. The manifest (OUTDIR/manifest.json) lists, per file, the wbv input options
to read it with and the exact samples (float64, JSON round-trip exact) each channel must have after
units and sensitivity, as computed here in float64.
"""

import csv
import json
import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pyuff
import scipy.io
import scipy.io.wavfile
import soundfile
from google.protobuf import descriptor_pb2, descriptor_pool, message_factory
from mcap.writer import Writer as McapWriter
from mcap_protobuf.writer import Writer as ProtobufWriter
from mcap_ros2.writer import Writer as Ros2Writer

G = 9.80665
out = Path(sys.argv[1])
out.mkdir(parents=True, exist_ok=True)
rng = np.random.default_rng(17)
manifest = []


def signal(n, fs, f=7.0, amp=1.0):
    """A seat-like test signal: a sine plus band-limited noise, |x| < amp."""
    t = np.arange(n) / fs
    x = 0.6 * np.sin(2 * np.pi * f * t) + 0.3 * np.tanh(rng.standard_normal(n))
    return amp * x / np.max(np.abs(x)) * 0.95


def add(file, fs, channels, **opts):
    manifest.append(
        {
            "file": file,
            "fs": fs,
            "options": opts,
            "channels": {k: [float(v) for v in vals] for k, vals in channels.items()},
        }
    )


# WAV, int16 (scipy), 2 channels at 256 Hz, sensitivities 49.05 and 20 (value of full scale).
fs, n = 256, 256 * 12
a, b = signal(n, fs), signal(n, fs, 3.0)
pcm = np.stack([np.round(a * 32767), np.round(b * 32767)], axis=1).astype(np.int16)
scipy.io.wavfile.write(out / "int16.wav", fs, pcm)
add(
    "int16.wav",
    fs,
    {
        "a_seat_z": pcm[:, 0].astype(np.float64) / 32768.0 * 49.05,
        "a_base_z": pcm[:, 1].astype(np.float64) / 32768.0 * 20.0,
    },
    column=["a_seat_z=1", "a_base_z=2"],
    sensitivity=["a_seat_z=49.05", "a_base_z=20"],
)

# WAV, 24-bit (soundfile), 3 channels at 200 Hz, in g.
fs, n = 200, 200 * 11
x = np.stack([signal(n, fs), signal(n, fs, 2.0), signal(n, fs, 9.0)], axis=1)
soundfile.write(out / "int24.wav", x, fs, subtype="PCM_24")
back, _ = soundfile.read(out / "int24.wav", dtype="int32")  # left-justified 24-bit in int32
i24 = (back >> 8).astype(np.float64)
add(
    "int24.wav",
    fs,
    {
        "a_seat_x": i24[:, 0] / 8388608.0 * 2.0 * G,
        "a_seat_y": i24[:, 1] / 8388608.0 * 2.0 * G,
        "a_seat_z": i24[:, 2] / 8388608.0 * 2.0 * G,
    },
    column=["a_seat_x=1", "a_seat_y=2", "a_seat_z=3"],
    sensitivity=["a_seat_x=2", "a_seat_y=2", "a_seat_z=2"],
    units=["g"],
)

# WAV, int32 (scipy), 1 channel at 1000 Hz.
fs, n = 1000, 1000 * 10
i32 = np.round(signal(n, fs) * 2**31 * 0.9).astype(np.int32)
scipy.io.wavfile.write(out / "int32.wav", fs, i32)
add(
    "int32.wav",
    fs,
    {"a_seat_z": i32.astype(np.float64) / 2**31 * 10.0},
    column=["a_seat_z=1"],
    sensitivity=["a_seat_z=10"],
)

# WAV, float32 (soundfile), 2 channels at 512 Hz, sensitivity 1.
fs, n = 512, 512 * 10
f32 = np.stack([signal(n, fs) * 3, signal(n, fs, 4.0) * 2], axis=1).astype(np.float32)
soundfile.write(out / "float32.wav", f32, fs, subtype="FLOAT")
add(
    "float32.wav",
    fs,
    {"a_seat_z": f32[:, 0].astype(np.float64), "a_base_z": f32[:, 1].astype(np.float64)},
    column=["a_seat_z=1", "a_base_z=2"],
    sensitivity=["a_seat_z=1", "a_base_z=1"],
)

# MAT v5 (scipy), a time vector, a row and a column vector, plus variables to skip.
fs, n = 500, 500 * 10
seat, base = signal(n, fs), signal(n, fs, 2.5)
scipy.io.savemat(
    out / "v5.mat",
    {
        "time": np.arange(n) / fs,
        "acc_seat": seat,
        "acc_base": base.reshape(-1, 1),
        "calib": np.eye(3),
        "note": "a string",
    },
)
add(
    "v5.mat",
    fs,
    {"a_seat_z": seat, "a_base_z": base},
    column=["a_seat_z=acc_seat", "a_base_z=acc_base"],
)
# Compressed (MATLAB -v7 style), single precision, channel names as variables, no time: --fs.
seat32 = signal(n, fs).astype(np.float32)
scipy.io.savemat(out / "v7.mat", {"a_seat_z": seat32}, do_compression=True)
add("v7.mat", fs, {"a_seat_z": seat32.astype(np.float64)}, fs_option=fs)

# UFF58 (pyuff), two time responses at 512 Hz, ASCII and binary.
fs, n = 512, 512 * 10
seat, base = signal(n, fs), signal(n, fs, 2.5)
for name, binary in [("ascii.uff", 0), ("binary.uff", 1)]:
    path = out / name
    if path.exists():
        path.unlink()
    u = pyuff.UFF(str(path))
    for i, (label, data) in enumerate([("seat z", seat), ("base z", base)]):
        u.write_sets(
            pyuff.prepare_58(
                binary=binary,
                id1=label,
                func_type=1,
                rsp_node=i + 1,
                rsp_dir=3,
                ref_node=0,
                ref_dir=0,
                data=data,
                x=np.arange(n) / fs,
                abscissa_spacing=1,
                abscissa_spec_data_type=17,
                ordinate_spec_data_type=12,
                orddenom_spec_data_type=0,
            ),
            mode="add",
        )
    add(
        name,
        fs,
        {"a_seat_z": seat, "a_base_z": base},
        column=['a_seat_z=seat z', "a_base_z=base z"],
        exact=bool(binary),
    )

# MCAP, JSON channel at 400 Hz (log times exact in ns), plus another topic.
fs, n = 400, 400 * 10
z, xx = signal(n, fs), signal(n, fs, 3.0)
with open(out / "json.mcap", "wb") as f:
    w = McapWriter(f)
    w.start()
    sid = w.register_schema("Imu", "jsonschema", b'{"type":"object"}')
    imu = w.register_channel("/imu", "json", sid)
    gps = w.register_channel("/gps", "json", 0)
    for i in range(n):
        t = i * 2_500_000
        msg = {"linear_acceleration": {"x": xx[i], "y": 0.0, "z": z[i]}, "seq": i}
        w.add_message(imu, log_time=t, publish_time=t, data=json.dumps(msg).encode())
        if i % 100 == 0:
            w.add_message(gps, log_time=t, publish_time=t, data=b'{"lat": 1.0}')
    w.finish()
add(
    "json.mcap",
    fs,
    {"a_seat_z": z, "a_seat_x": xx},
    topic="/imu",
    column=["a_seat_z=linear_acceleration.z", "a_seat_x=linear_acceleration.x"],
)

# MCAP, protobuf channel (schema: a FileDescriptorSet built here), at 250 Hz, float and double.
fdp = descriptor_pb2.FileDescriptorProto(name="wbv_test.proto", package="wbv_test", syntax="proto3")
vec = fdp.message_type.add(name="Vector3")
for k, nm in enumerate("xyz"):
    vec.field.add(name=nm, number=k + 1, type=descriptor_pb2.FieldDescriptorProto.TYPE_DOUBLE)
imu_t = fdp.message_type.add(name="Imu")
imu_t.field.add(
    name="linear_acceleration",
    number=1,
    type=descriptor_pb2.FieldDescriptorProto.TYPE_MESSAGE,
    type_name=".wbv_test.Vector3",
)
imu_t.field.add(name="temperature", number=2, type=descriptor_pb2.FieldDescriptorProto.TYPE_FLOAT)
imu_t.field.add(
    name="samples", number=3, type=descriptor_pb2.FieldDescriptorProto.TYPE_FLOAT,
    label=descriptor_pb2.FieldDescriptorProto.LABEL_REPEATED,
)
pool = descriptor_pool.DescriptorPool()
pool.Add(fdp)
Imu = message_factory.GetMessageClass(pool.FindMessageTypeByName("wbv_test.Imu"))
fs, n = 250, 250 * 10
z, s2 = signal(n, fs), signal(n, fs, 5.0).astype(np.float32)
with open(out / "protobuf.mcap", "wb") as f:
    w = ProtobufWriter(f)
    for i in range(n):
        m = Imu()
        m.linear_acceleration.z = z[i]
        m.temperature = 21.5
        m.samples.extend([0.0, float(s2[i])])
        w.write_message("/imu", m, log_time=i * 4_000_000, publish_time=i * 4_000_000)
    w.finish()
add(
    "protobuf.mcap",
    fs,
    {"a_seat_z": z, "a_back_x": s2.astype(np.float64)},
    topic="/imu",
    column=["a_seat_z=linear_acceleration.z", "a_back_x=samples[1]"],
)

# MCAP, ROS 2 CDR channel (mcap-ros2-support), at 200 Hz, time from the header stamp.
msgdef = """std_msgs/Header header
geometry_msgs/Vector3 linear_acceleration
float32 temperature
================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
================================================================================
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec
================================================================================
MSG: geometry_msgs/Vector3
float64 x
float64 y
float64 z
"""
fs, n = 200, 200 * 10
z = signal(n, fs)
with open(out / "ros2.mcap", "wb") as f:
    w = Ros2Writer(f)
    schema = w.register_msgdef("wbv_test/msg/Imu", msgdef)
    for i in range(n):
        ns = 1_700_000_000 * 10**9 + i * 5_000_000
        msg = {
            "header": {"stamp": {"sec": ns // 10**9, "nanosec": ns % 10**9}, "frame_id": "seat"},
            "linear_acceleration": {"x": 0.0, "y": 0.0, "z": z[i]},
            "temperature": 20.0,
        }
        # Log times jitter like a real logger's; the stamps in the header are uniform.
        lt = ns + int(rng.integers(0, 2_000_000))
        w.write_message("/imu/data", schema, msg, log_time=lt, publish_time=lt)
    w.finish()
add(
    "ros2.mcap",
    fs,
    {"a_seat_z": z},
    topic="/imu/data",
    column=["a_seat_z=linear_acceleration.z", "t_s=header.stamp"],
)

# CSV of a European logger (Python's csv module): BOM, `;`, decimal commas, a units row, time
# printed to 1 ms at 256 Hz (rounding up to 13 % of the step), acceleration in g.
fs, n = 256, 256 * 12
z, b = signal(n, fs) * 0.3, signal(n, fs, 2.0) * 0.2
with open(out / "logger.csv", "w", newline="", encoding="utf-8-sig") as f:
    wr = csv.writer(f, delimiter=";", quoting=csv.QUOTE_MINIMAL)
    wr.writerow(["Time", "Acc Z seat", "Acc Z base", "Status"])
    wr.writerow(["s", "g", "g", ""])
    for i in range(n):
        wr.writerow([f"{i / fs:.3f}".replace(".", ","), repr(float(z[i])).replace(".", ","),
                     repr(float(b[i])).replace(".", ","), "OK"])
add(
    "logger.csv",
    fs,
    {"a_seat_z": z * G, "a_base_z": b * G},
    column=["a_seat_z=Acc Z seat", "a_base_z=Acc Z base"],
)

# TSV without a time column, quoted headers with units: --fs.
fs, n = 320, 320 * 10
z = signal(n, fs)
with open(out / "no-time.tsv", "w", newline="") as f:
    wr = csv.writer(f, delimiter="\t", quoting=csv.QUOTE_NONNUMERIC)
    wr.writerow(["a_seat_z [m/s^2]"])
    for v in z:
        wr.writerow([float(v)])
add("no-time.tsv", fs, {"a_seat_z": z}, fs_option=fs)


# A spreadsheet's CSV export in a decimal-comma locale (Python's csv module, Excel's dialect):
# `,` between fields, every field quoted, decimal commas inside the quotes (`"0,001953"`), CRLF
# line ends, no units row; time to 6 decimals at 512 Hz. Line 2 is numbers, never a units row.
fs, n = 512, 512 * 12
z, b = signal(n, fs) * 2.0, signal(n, fs, 3.0)
t_text = [f"{i / fs:.6f}".replace(".", ",") for i in range(n)]
z_text = [f"{v:.6f}".replace(".", ",") for v in z]
b_text = [f"{v:.6f}".replace(".", ",") for v in b]
with open(out / "sheet-comma.csv", "w", newline="") as f:
    wr = csv.writer(f, dialect="excel", quoting=csv.QUOTE_ALL)
    wr.writerow(["Time", "Acc Z seat", "Acc Z base"])
    for row in zip(t_text, z_text, b_text):
        wr.writerow(row)


def comma_value(texts):
    """The samples a decimal-comma text holds, parsed here with Python's float."""
    return [float(v.replace(",", ".")) for v in texts]


add(
    "sheet-comma.csv",
    fs,
    {"a_seat_z": comma_value(z_text), "a_base_z": comma_value(b_text)},
    column=["a_seat_z=Acc Z seat", "a_base_z=Acc Z base"],
)

# The same export with a BOM and a units row (s; m/s²; g), channels named by the measured-run
# convention: the units row is read, the g column converted.
with open(out / "sheet-comma-units.csv", "w", newline="", encoding="utf-8-sig") as f:
    wr = csv.writer(f, dialect="excel", quoting=csv.QUOTE_ALL)
    wr.writerow(["t_s", "a_seat_z", "a_base_z"])
    wr.writerow(["s", "m/s²", "g"])
    for row in zip(t_text, z_text, b_text):
        wr.writerow(row)
add(
    "sheet-comma-units.csv",
    fs,
    {"a_seat_z": comma_value(z_text), "a_base_z": [v * G for v in comma_value(b_text)]},
)

# numpy.savetxt of a seat channel recorded in g with gravity removed (mean zero) and no unit
# anywhere: nothing in the numbers tells g from m/s², so every figure must say it assumes m/s².
# 512 Hz with a time column, 30 s; tests/first_hour.rs reads it with and without --units g.
fs, n = 512, 512 * 30
t = np.arange(n) / fs
g_seat = 0.09 * np.sin(2 * np.pi * 5.0 * t) + 0.02 * np.tanh(rng.standard_normal(n))
np.savetxt(out / "g-seat.csv", np.column_stack([t, g_seat]), fmt="%.6f", delimiter=",",
           header="t_s,a_seat_z", comments="")
add("g-seat.csv", fs, {"a_seat_z": [float(f"{v:.6f}") for v in g_seat]})

(out / "manifest.json").write_text(json.dumps(manifest))
print(f"input fixtures: {len(manifest)} files in {out}")
