"""birotor-export and birotor.read_log against hostile logs (python_export_confinement):
every file stays inside --output-dir, a planted link is never written through, and
a NUL in a channel, a cut message, a cut event, a FIFO, a device, a folder, an
oversized length field and a 100 000-channel log each end in one error line, exit 1.
Usage: export_confinement_test.py PYTHON_DIR (build/python: the package and birotor-export)."""

import os
import signal
import struct
import subprocess
import sys
import tempfile

PYTHON_DIR = os.path.abspath(sys.argv[1])
sys.path.insert(0, PYTHON_DIR)
import birotor  # noqa: E402

EXPORT = [sys.executable, os.path.join(PYTHON_DIR, "birotor-export")]
FORCE = birotor.force_estimate_t()
FORCE.force_n = [21.5, 22.5]
FORCE.status = FORCE.STATUS_VALID | FORCE.STATUS_THRUST_DEFICIT


def event(number, channel, data, utime=1000):
    raw = channel.encode("utf-8") if isinstance(channel, str) else channel
    return struct.pack(">Iqqii", birotor.log_reader.SYNC_WORD, number, utime * (number + 1), len(raw), len(data)) \
        + raw + data


def write_log(path, events):
    with open(path, "wb") as f:
        f.write(b"".join(events))
    return path


def export(log, output_dir, *options):
    # A timeout: a FIFO that blocked the reader would hang here.
    env = dict(os.environ, PYTHONPATH=PYTHON_DIR)
    result = subprocess.run(EXPORT + [log, "--output-dir", output_dir, *options], capture_output=True, text=True,
                            timeout=60, env=env)
    return result.returncode, result.stderr.strip()


def files_under(folder):
    return sorted(os.path.relpath(os.path.join(d, f), folder) for d, _, names in os.walk(folder) for f in names)


def expect_refused(work, log, needle, *options):
    out = os.path.join(work, "refused")
    status, err = export(log, out, *options)
    assert status == 1, (log, status, err)
    assert err.startswith("birotor-export: error: ") and "\n" not in err and "Traceback" not in err, err
    assert needle in err, (needle, err)
    assert files_under(out) == [], files_under(out)  # nothing written, no temporary left
    return err


def test_channel_names_stay_inside(work):
    outside = os.path.join(work, "outside")
    os.mkdir(outside)
    names = ["../x", "../../escaped", os.path.join(outside, "abs"), ".hidden", "a/b", "100%", "BIROTOR_FORCE"]
    log = write_log(os.path.join(work, "names.lcm"), [event(i, n, FORCE.encode()) for i, n in enumerate(names)])
    out = os.path.join(work, "names")
    status, err = export(log, out)
    assert status == 0, err
    expected = ["%2E%2E%2Fx.csv", "%2E%2E%2F%2E%2E%2Fescaped.csv",
                "".join(c if c.isalnum() or c in "_-" else f"%{ord(c):02X}" for c in os.path.join(outside, "abs")) + ".csv",
                "%2Ehidden.csv", "a%2Fb.csv", "100%25.csv", "BIROTOR_FORCE.csv"]
    assert files_under(out) == sorted(expected), files_under(out)
    assert files_under(outside) == [] and not os.path.exists(os.path.join(work, "x.csv")), "a file escaped"


def test_planted_links_not_followed(work):
    out, victim = os.path.join(work, "planted"), os.path.join(work, "victim.txt")
    os.mkdir(out)
    with open(victim, "w") as f:
        f.write("keep\n")
    # The old temporary name and the final name, both links to the victim.
    os.symlink(victim, os.path.join(out, "BIROTOR_FORCE.csv.tmp"))
    os.symlink(victim, os.path.join(out, "BIROTOR_FORCE.csv"))
    log = write_log(os.path.join(work, "one.lcm"), [event(0, "BIROTOR_FORCE", FORCE.encode())])
    status, err = export(log, out)
    assert status == 0, err
    assert open(victim).read() == "keep\n", "written through a planted link"
    assert not os.path.islink(os.path.join(out, "BIROTOR_FORCE.csv")), "the link was not replaced"
    header, row = open(os.path.join(out, "BIROTOR_FORCE.csv")).read().splitlines()
    columns = dict(zip(header.split(","), row.split(",")))
    # status 257 = VALID (1) + THRUST_DEFICIT (256): force_estimate_t.lcm.
    assert columns["status"] == "257" and columns["STATUS_VALID"] == "1" and columns["STATUS_THRUST_DEFICIT"] == "1"
    assert columns["STATUS_CONVERGING"] == "0" and columns["time_s [s]"] == "0.0", columns


def test_damaged_logs_refused(work):
    good = event(0, "BIROTOR_FORCE", FORCE.encode())
    cases = [
        ([good, event(1, b"BIROTOR\0FORCE", FORCE.encode())], "holds a NUL byte"),
        ([good, event(1, "BIROTOR_FORCE", FORCE.encode()[:30])], "does not decode as force_estimate_t"),
        ([good, event(1, "BIROTOR_FORCE", FORCE.encode())[:40]], "runs past the end of the file"),
        ([good, good[:10]], "not a whole event header"),
        ([good, event(1, "C" * 64, b"")], "channel name of 64 bytes"),
        ([good, struct.pack(">Iqqii", birotor.log_reader.SYNC_WORD, 1, 0, 5, (16 << 20) + 1) + b"CHANN"],
         "claims 16777217 bytes"),
        ([b"not a log at all, just text........"], "no event at offset 0"),
    ]
    for i, (events, needle) in enumerate(cases):
        expect_refused(work, write_log(os.path.join(work, f"damaged{i}.lcm"), events), needle)


def test_special_files_refused(work):
    fifo = os.path.join(work, "fifo.lcm")
    os.mkfifo(fifo)
    expect_refused(work, fifo, "not a regular file")
    expect_refused(work, "/dev/zero", "not a regular file")
    expect_refused(work, work, "not a regular file")
    for path in (fifo, "/dev/zero"):
        try:
            birotor.read_log(path)
            raise AssertionError(f"read_log read {path}")
        except birotor.LogError as e:
            assert "not a regular file" in str(e), e


def test_channel_cap(work):
    # 100 000 channels of one 8-byte message of an unknown type: refused at
    # the default cap (64), before any file is written.
    log = write_log(os.path.join(work, "many.lcm"), [event(i, f"C{i}", b"\0" * 8) for i in range(100000)])
    expect_refused(work, log, "more than 64 channels")
    expect_refused(work, log, "more than 1000 channels", "--max-channels", "1000")
    small = write_log(os.path.join(work, "three.lcm"), [event(i, f"C{i}", b"\0" * 8) for i in range(3)])
    out = os.path.join(work, "three")
    assert export(small, out, "--max-channels", "3")[0] == 0
    assert files_under(out) == ["C0.csv", "C1.csv", "C2.csv"], files_under(out)
    assert export(small, out, "--max-channels", "0")[0] == 2


def main():
    signal.alarm(240)  # a hang (a FIFO opened for reading) fails the test instead of stalling CTest
    with tempfile.TemporaryDirectory(prefix="birotor-confine-") as work:
        for test in (test_channel_names_stay_inside, test_planted_links_not_followed, test_damaged_logs_refused,
                     test_special_files_refused, test_channel_cap):
            test(work)
            print(f"ok: {test.__name__}")
    print("PASS")


if __name__ == "__main__":
    main()
