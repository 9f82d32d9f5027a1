"""Time of the Python binding on every example in data/, against the CLI: min of N runs.
Usage: python bindings/bench/overhead.py [N]   (GCS_CLI: the CLI, default target/release/gcs)"""
import os, subprocess, sys, time
from pathlib import Path
import gcs

n = int(sys.argv[1]) if len(sys.argv) > 1 else 5
root = Path(__file__).resolve().parents[2]
os.chdir(root)
cli = os.environ.get("GCS_CLI", "target/release/gcs")
files = sorted(str(p) for p in Path("data").rglob("*") if p.suffix.lower() in (".ron", ".slvs", ".fcstd", ".json"))

def best(f):
    t = []
    for _ in range(n):
        s = time.perf_counter(); f(); t.append(time.perf_counter() - s)
    return min(t)

def py():
    for f in files:
        for m in gcs.load_all(f):
            m.analyze().to_dict()

t_cli = best(lambda: subprocess.run([cli, "analyze", "--format", "json", "--jobs", "1", "data"], stdout=subprocess.DEVNULL, check=False))
t_py = best(py)
print(f"{len(files)} files: CLI (one process, --jobs 1) {t_cli*1000:.0f} ms; Python in-process {t_py*1000:.0f} ms ({t_py/t_cli:.2f}x)")
