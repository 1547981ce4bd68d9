#!/usr/bin/env python3
"""scripts/drum_readings.py on synthetic runs whose surface is known: straight surfaces at 30 and
36 deg read 30 and 36 deg by every line fit and by highest-to-lowest, grouped by speed, and the
change comes out in pooled sd. Usage: drum_readings_test.py SCRIPT"""
import json
import math
import os
import subprocess
import sys
import tempfile

script = sys.argv[1]
with tempfile.TemporaryDirectory() as tmp:
    runs = []
    for rpm, angle, wobble in ((5, 30.0, -0.5), (5, 30.0, 0.5), (15, 36.0, -0.5), (15, 36.0, 0.5)):
        d = os.path.join(tmp, f"rpm{rpm}-{len(runs)}")
        os.makedirs(d)
        with open(os.path.join(d, "metrics.json"), "w") as f:
            json.dump({"speed_rpm": rpm}, f)
        slope = math.tan(math.radians(angle + wobble))
        with open(os.path.join(d, "drum_surface.csv"), "w") as f:
            f.write("time_s,x_m,z_m\n")
            for t in (1.5, 2.0):
                for i in range(21):
                    x = -0.08 + 0.008 * i
                    f.write(f"{t},{x},{slope * x}\n")
        runs.append(d)
    out = subprocess.run([sys.executable, script, *runs], check=True, capture_output=True,
                         text=True).stdout
    print(out)
    rows = {line[:9].strip(): line[9:].split() for line in out.splitlines()[1:]}
    for key in ("fit 0.4", "fit 0.6", "fit 1.0", "hi-lo", "steepest"):
        cols = rows[key]
        assert cols[0] == "30.00" and cols[3] == "36.00", (key, cols)
        assert cols[6] == "+6.00", (key, cols)
    # pooled sd of the runs' angles: 0.5 * sqrt(2) = 0.707 deg, so +6.00 deg is +8.49 of it
    assert rows["fit 0.6"][8] == "(+8.49)", rows["fit 0.6"]
    bad = subprocess.run([sys.executable, script, tmp], capture_output=True, text=True)
    assert bad.returncode != 0 and "metrics.json" in bad.stderr, bad.stderr
print("ok")
