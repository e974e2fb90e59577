#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Issue 14 experiment (docs/method.md, "Bias and standard deviations, measured"): simulate RUNS planar 2R logs,
# identify each with --method both, compare the spread of the estimates with the reported std.
# Usage: scripts/identify_monte_carlo.py [--jacobid build/host-tools/jacobid] [--runs 40] [-- identify options]
import argparse, json, math, os, subprocess, sys, concurrent.futures as cf
p = argparse.ArgumentParser()
p.add_argument("--jacobid", default="build/host-tools/jacobid")
p.add_argument("--runs", type=int, default=40)
p.add_argument("--seed0", type=int, default=100)
p.add_argument("--noise-seed0", type=int, default=500)
p.add_argument("--duration", default="25")
p.add_argument("--noise", default="0.05,0.01")
p.add_argument("--work", default="/tmp/jacobid-monte-carlo")
p.add_argument("--tag", default="base")
p.add_argument("--jobs", type=int, default=2)
p.add_argument("--sim-extra", default="")
p.add_argument("extra", nargs="*", help="extra identify options")
a = p.parse_args()
os.makedirs(a.work, exist_ok=True)
robot = os.path.join(a.work, "robot.yaml")
open(robot, "w").write("model: planar2r\nL1: 0.5\nfriction: {coulomb: smooth, alpha: 100}\n")
def one(i):
    s, ns = a.seed0 + i, a.noise_seed0 + i
    log = f"{a.work}/log_{s}_{ns}{a.sim_extra.replace(' ','_')}.csv"; truth = log[:-4] + ".truth.json"
    if not os.path.exists(truth):
        subprocess.run([a.jacobid, "simulate", "--robot", robot, "--seed", str(s), "--noise-seed", str(ns), "--duration", a.duration,
                        "--torque-noise", a.noise, "--out", log, "--truth", truth, "--quiet"] + a.sim_extra.split(), check=True)
    out = subprocess.run([a.jacobid, "identify", "--robot", robot, "--in", log, "--format", "json", "--method", "both", "--quiet"] + a.extra,
                         check=True, capture_output=True, text=True).stdout
    return json.load(open(truth))["parameters"], json.loads(out)
with cf.ThreadPoolExecutor(a.jobs) as ex: res = list(ex.map(one, range(a.runs)))
json.dump(res, open(f"{a.work}/{a.tag}.json", "w"))
methods = list(res[0][1]["methods"].keys())
rms = {}
print(f"{'method':12} {'param':6} {'mean err %':>10} {'|m|/sem':>8} {'spread/std':>10} {'in 2std':>8} {'rms err %':>9} {'std method'}")
for m in methods:
    for name in res[0][1]["methods"][m]["parameters"]:
        if name not in res[0][0]: continue
        t = res[0][0][name]
        v = [r[1]["methods"][m]["parameters"][name]["value"] for r in res]
        sd = [r[1]["methods"][m]["parameters"][name]["std"] for r in res]
        tr = [r[0][name] for r in res]
        e = [x - y for x, y in zip(v, tr)]
        n = len(e); me = sum(e)/n
        emp = math.sqrt(sum((x-me)**2 for x in e)/(n-1)); ms = sum(sd)/n
        cover = sum(abs(x) <= 2*s for x, s in zip(e, sd))/n
        r = math.sqrt(sum(x*x for x in e)/n); rms[(m,name)] = r
        print(f"{m:12} {name:6} {100*me/t:+10.3f} {abs(me)/(emp/math.sqrt(n)):8.2f} {emp/ms:10.2f} {100*cover:7.0f}% {100*r/abs(t):9.3f} {res[0][1]['methods'][m].get('std_method','')}")
if len(methods) == 2:
    print("RMS ratio jacobi/butterworth: " + ", ".join(f"{k[1]} {rms[k]/rms[('butterworth',k[1])]:.2f}" for k in rms if k[0]=='jacobi'))
