#!/usr/bin/python3
"""Writes docs/results.md and docs/images/*.png from the files scripts/bench
measured (accuracy.csv/.md, physical.md, rates.csv, frame-times.csv, zwidth.csv/.md, procedure.csv/.md and
procedure-*.txt, stability.txt), and physical.md into docs/accuracy.md between its markers."""
import argparse, csv, datetime, math, os, platform, re, subprocess
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

ap = argparse.ArgumentParser()
ap.add_argument("--data", required=True)
ap.add_argument("--docs", required=True)
a = ap.parse_args()
img = os.path.join(a.docs, "images")
os.makedirs(img, exist_ok=True)

def num(x):
    try:
        v = float(x)
        return v if math.isfinite(v) else float("nan")
    except ValueError:
        return float("nan")

def fmt(v, p=3):
    return "–" if v is None or not math.isfinite(v) else f"{v:.{p}g}"

acc = list(csv.DictReader(open(os.path.join(a.data, "accuracy.csv"))))
allrows = [r for r in acc if r["scene"] == "all"]
rates_path = os.path.join(a.data, "rates.csv")
rates = list(csv.DictReader(open(rates_path))) if os.path.exists(rates_path) else []
stab = open(os.path.join(a.data, "stability.txt")).read().splitlines()
def optional_csv(name):
    path = os.path.join(a.data, name)
    return list(csv.DictReader(open(path))) if os.path.exists(path) else []
def optional_text(name):
    path = os.path.join(a.data, name)
    return open(path).read() if os.path.exists(path) else ""
zwidth = optional_csv("zwidth.csv")
procedure = optional_csv("procedure.csv")
frame_times = optional_csv("frame-times.csv")  # millsim bench procedure: the §8.2 procedure's frames by phase
ARM = "M=0.554kg B=6.45Ns/m K=135N/m"  # the measured arm's grip: the headline's Z-width
def zw(rend, hand=ARM):
    return next((r for r in zwidth if r["renderer"] == rend and r["hand"] == hand), None)
def total_score(rend):
    return next((r["total"] for r in procedure if r["algorithm"] == rend), None)
renderers = sorted({r["renderer"] for r in allrows})
colors = dict(zip(renderers, ["tab:blue", "tab:orange", "tab:green", "tab:red"]))

# ---- Pareto: time against the physical error, one curve per renderer (bench physical --sweep-voxel 0.1:
# each resolution field's values at h = 0.1 mm, against the rigid tool's constrained pose)
sweep = [r for r in optional_csv("physical.csv") if r.get("scene") == "all" and abs(num(r["h_mm"]) - 0.1) < 1e-9
         and r.get("resolution", "default") != "default"]  # the defaults are one of each sweep's values
fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
for ax, metric, title in [(axes[0], "force_rms", "force error against the physical reference (RMS, relative)"),
                          (axes[1], "dir_rms_deg", "direction error against the physical reference (RMS, °)")]:
    for rend in sorted({r["renderer"] for r in sweep}):
        pts = sorted({(num(r["p50_us"]), num(r[metric]), r["resolution"]) for r in sweep
                      if r["renderer"] == rend and math.isfinite(num(r[metric])) and num(r[metric]) > 0})
        # Pareto front: the best error at each time budget.
        front, best = [], float("inf")
        for t, e, lab in pts:
            if e < best:
                front.append((t, e, lab)); best = e
        color = colors.get(rend, "tab:gray")
        ax.scatter([p[0] for p in pts], [p[1] for p in pts], color=color, alpha=0.35, s=14)
        ax.plot([p[0] for p in front], [p[1] for p in front], "-o", color=color, label=rend, ms=4)
        for t, e, lab in front:
            ax.annotate(lab, (t, e), fontsize=6, xytext=(3, 3), textcoords="offset points")
    ax.set_xscale("log"); ax.set_yscale("log")
    ax.set_xlabel("frame time p50 (µs), held poses of the analytic scenes"); ax.set_ylabel(title, fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
fig.suptitle("Run time against physical error (h = 0.1 mm; each point a resolution, line = Pareto front)")
fig.tight_layout(); fig.savefig(os.path.join(img, "pareto.png"), dpi=110); plt.close(fig)

# ---- Convergence in h at the default resolution
fig, ax = plt.subplots(figsize=(5.5, 4))
for rend in renderers:
    pts = sorted((num(r["h_mm"]), num(r["force_rms"]), num(r["torque_rms"])) for r in allrows
                 if r["renderer"] == rend and r["resolution"] == "default")
    ax.plot([p[0] for p in pts], [p[1] for p in pts], "-o", color=colors[rend], label=rend + " force")
    ax.plot([p[0] for p in pts], [p[2] for p in pts], "--s", color=colors[rend], label=rend + " torque")
ax.set_xscale("log"); ax.set_yscale("log"); ax.set_xlabel("voxel size h (mm)"); ax.set_ylabel("RMS relative error")
ax.grid(True, which="both", alpha=0.3); ax.legend(fontsize=7); fig.tight_layout()
fig.savefig(os.path.join(img, "convergence.png"), dpi=110); plt.close(fig)

# ---- Stability lines
scen = [l.split(" | ") for l in stab if re.match(r"^\w+ \| (static|slide|impact|release)", l)]
falls = [l for l in stab if "highest safe speed" in l]
fuzz = [l for l in stab if "| fuzz " in l]
known = sorted({l for l in stab if l.startswith("KNOWN ISSUE")})
def field(parts, key):
    for p in parts:
        if p.startswith(key):
            m = re.search(r"-?[0-9.e+-]+", p[len(key):])
            return num(m.group(0)) if m else float("nan")
    return float("nan")

safe = {}
for l in falls:
    m = re.match(r"(\w+) \| plate ([0-9.]+) mm \| highest safe speed ([0-9.]+) m/s( \(all speeds tried\))?", l)
    if m:
        safe.setdefault(m.group(1), []).append((m.group(2), m.group(3), bool(m.group(4))))

# ---- Machine
cpu = "unknown CPU"
for line in open("/proc/cpuinfo"):
    if line.startswith("model name"):
        cpu = line.split(":", 1)[1].strip(); break
cores = os.cpu_count()
mhz = ""
for line in open("/proc/cpuinfo"):
    if line.startswith("cpu MHz"):
        mhz = f", {float(line.split(':')[1]):.0f} MHz"; break
load = open("/proc/loadavg").read().split()[:3]

COARSE, FINE = "256x256x176 @ 0.1 mm", "512x512x352 @ 0.05 mm"
def rate_row(rend, label, grid=COARSE):
    for r in rates:
        if r["renderer"] == rend and r["resolution"] == label and r.get("grid", COARSE) == grid \
                and (r.get("pose") or "gentle") == "gentle":
            return r
    return None

out = []
w = out.append
w("# Results: run time against error, the paper's §8, and stability\n")
w(f"Generated by `scripts/bench` on {datetime.datetime.now().strftime('%Y-%m-%d %H:%M')} — {cpu}, "
  f"{cores} cores{mhz}, load average {' '.join(load)} (the machine is shared: times are upper bounds), "
  f"{platform.system()} {platform.release()}. Methods: [stability.md](stability.md) and [accuracy.md](accuracy.md).\n")

w("## Headline\n")
def ft(rend, phase, res="default"):
    for r in frame_times:
        if r["renderer"] == rend and r["resolution"] == res and r["phase"] == phase:
            return r
    return None
w("Frame times are the §8.2 procedure's (the default lesson replayed in simulated time, every frame on the haptic "
  "thread's CPU clock: `millsim bench procedure`, section below); goal p99 ≤ 50 µs and worst ≤ 250 µs. The gentle "
  "§8.1 pose's p99 is kept beside them.\n")
physical_rows = optional_csv("physical.csv")
def phys(rend):
    for r in physical_rows:
        if r["renderer"] == rend and r["scene"] == "all" and abs(num(r["h_mm"]) - 0.1) < 1e-9:
            return r
    return None
w("| algorithm | §8.2 frames p99 / worst (µs) | §8.2 milling frames p99 / worst (µs) | §8.1 gentle pose p99 (µs) | force error RMS, physical reference / own law (h = 0.1 mm) | direction error RMS, physical (°) | "
  "torque error RMS, physical / own law | largest stable stiffness, measured arm (× default) | highest safe speed through plates "
  "(1/2/4 voxels, 1 mm) | passivity (CI grips) | §8.2 score (lower is better) |")
w("|---|---|---|---|---|---|---|---|---|---|---|")
paper_res = {"LineProxyRenderer": "vertexCount=51", "SurfacePointRenderer": "slices=20", "BarbicRenderer": "pointShellScale=3"}
for rend in renderers:
    rr = rate_row(rend, paper_res.get(rend, "default"))
    rf = rate_row(rend, paper_res.get(rend, "default"), FINE)
    d = [r for r in allrows if r["renderer"] == rend and r["resolution"] == "default" and abs(num(r["h_mm"]) - 0.1) < 1e-9]
    s = safe.get(rend, [])
    speeds = ", ".join((">" if all_ else "") + v for _, v, all_ in s) + " m/s" if s else "–"
    fails = [p for p in scen if p[0] == rend and "FAIL" in p[-1]]
    z = zw(rend)
    zs = "–" if not z else (f"{num(z['largest_stable']):.0f} N/m {z['field']} (×{fmt(num(z['largest_stable']) / num(z['default']), 2)}), "
                            f"felt {num(z['rendered_at_largest']):.0f} N/m" + ("" if num(z["first_unstable"]) > 0 else ", all tried"))
    edge = [r for r in acc if r["renderer"] == rend and r["scene"] == "edge" and r["resolution"] == "default"
            and abs(num(r["h_mm"]) - 0.1) < 1e-9 and math.isfinite(num(r["torque_rms"]))]
    fa, fm = ft(rend, "all"), ft(rend, "milling")
    w(f"| {rend} | {fmt(num(fa['p99_us'])) + ' / ' + fmt(num(fa['max_us'])) if fa else '–'} | "
      f"{fmt(num(fm['p99_us'])) + ' / ' + fmt(num(fm['max_us'])) if fm else '–'} | "
      f"{fmt(num(rr['p99_us'])) + ' (' + paper_res.get(rend) + ')' if rr else '–'} | "
      f"{(fmt(num(phys(rend)['force_rms'])) + ' / ') if phys(rend) else ''}{fmt(num(d[0]['force_rms'])) if d else '–'} | "
      f"{fmt(num(phys(rend)['dir_rms_deg'])) if phys(rend) else '–'} | {(fmt(num(phys(rend)['torque_rms'])) + ' / ') if phys(rend) else ''}{fmt(num(d[0]['torque_rms'])) if d and edge else '– (own law not modelled)'} | {zs} | {speeds} | "
      f"{'all pass' if not fails else str(len(fails)) + ' of ' + str(len([p for p in scen if p[0] == rend])) + ' runs fail (known issues below)'} | "
      f"{total_score(rend) or '–'} |")
w("")

w("## Accuracy\n")
w("References, metrics and normalisation: [accuracy.md](accuracy.md). Every row is all five scenes together; "
  "the full per-scene data is in `build/<preset>/bench-results/accuracy.csv` after a run.\n")
w(open(os.path.join(a.data, "accuracy.md")).read())
w("\n![Convergence in h](images/convergence.png)\n")

physical = optional_text("physical.md")
if physical:
    w("## Against the physical reference\n")
    w("Each renderer at its defaults against the constrained pose of the rigid tool (the non-penetrating pose nearest "
      "the device in the coupling metric), with the own-law figure above beside it; method, metrics and the per-scene "
      "table: [accuracy.md](accuracy.md#physical-reference).\n")
    w(physical.split("\n\nPer scene")[0] + "\n")
    w("Run time against the physical error over each renderer's resolution fields (`millsim bench physical "
      "--sweep-voxel 0.1`; the table is in [accuracy.md](accuracy.md#physical-reference)): pick the resolution for "
      "the error you need.\n\n![Pareto](images/pareto.png)\n")

w("## Frame time under the real workload: the §8.2 procedure by phase\n")
w("`millsim bench procedure` replays `x3d/default.x3d` through `x3d/trajectories/section-8-2.csv` in simulated time "
  "with each renderer in the registry, and times every haptic frame (device, step, milling, publishing) on the thread's "
  "CPU clock, so that preemption stays out (frames that lost the CPU are counted by `millsim run`, which logs both "
  "clocks). Phases: *free* (no contact), *contact* (button off, tool within 5° of upright), *lean* (button off, leaning "
  "5° or more: the shaft on the hole's edge), *milling* (button held, in contact). *Control*: a loop of constant "
  "arithmetic as long as the phase's median frame, timed in the same run: its p99 above its p50 is what this machine "
  "adds to any frame that long (the kernel's 1 kHz tick and interrupts are charged to the running thread), so a "
  "renderer's p99 near the control's is no tail of its own. *Compiled afresh*: the brute-force variant of a milling "
  "frame, the renderer compiled again against the milled volume (for #3 a whole point-shell rebuild), timed on every "
  "100th milling frame, against the incremental update's median.\n")
if frame_times:
    w("| renderer | resolution | phase | frames | p50 (µs) | p99 (µs) | p99.9 (µs) | max (µs) | control p99 / p99.9 (µs) | compiled afresh p50 (µs) |")
    w("|---|---|---|---|---|---|---|---|---|---|")
    for r in frame_times:
        brute = (fmt(num(r["brute_p50_us"])) + f" ({fmt(num(r['brute_p50_us']) / max(1e-9, num(r['p50_us'])), 3)}×)"
                 if r["phase"] == "milling" and num(r["brute_samples"]) > 0 else "")
        w(f"| {r['renderer']} | {r['resolution']} | {r['phase']} | {r['frames']} | {fmt(num(r['p50_us']))} | "
          f"{fmt(num(r['p99_us']))} | {fmt(num(r['p999_us']))} | {fmt(num(r['max_us']))} | "
          f"{fmt(num(r['control_p99_us']))} / {fmt(num(r['control_p999_us']))} | {brute} |")
else:
    w("(not measured in this run)")
w("")

RES_BEGIN = "<!-- resolution:begin (scripts/plot-resolution writes this block) -->"
RES_END = "<!-- resolution:end -->"
w("## Cost against resolution: micro-CT voxels\n")
w("`millsim bench resolution` opens the default lesson with its tooth phantom at 100, 50 and 25 µm voxels (the "
  "same 25.6 × 25.6 × 17.6 mm box: 256·256·176 up to 1024·1024·704 voxels) and, at each size, times the load "
  "(volumes, tissues, regions; wall clock) with the process's peak resident memory, then replays the §8.2 procedure "
  "with every renderer as the section above does. Micro-CT scans of extracted teeth are 10–40 µm. The table and "
  "the plot are written by `scripts/plot-resolution` (scripts/bench runs both); the growth exponents are "
  "least-squares slopes on log-log axes: a frame cost that follows the contact, not the voxel count, has an exponent "
  "near 0.\n")
# The block is kept from the last time scripts/plot-resolution wrote it.
previous = open(os.path.join(a.docs, "results.md")).read() if os.path.exists(os.path.join(a.docs, "results.md")) else ""
kept = previous[previous.index(RES_BEGIN) + len(RES_BEGIN):previous.index(RES_END)].strip() \
    if RES_BEGIN in previous and RES_END in previous else "(not measured yet)"
w(RES_BEGIN + "\n" + kept + "\n" + RES_END + "\n")

w("## The paper's §8.1: frame time and equivalent rate\n")
w("Our figure is the compute time of one renderer step on the tooth phantom, on the thread's CPU clock, without device "
  "I/O; the paper's is the whole haptic loop on a 3.3 GHz Pentium 4 (from its rates, shared notes). Equivalent rate = "
  "1 / mean frame time. Two poses, the shaft leaning 15° and circling in both: *gentle*, the burr pressed 0.3 mm into "
  "the unmilled occlusal surface (the earlier table); *deep*, the burr pressed 0.3 mm into the bottom of a 2.5 mm hole "
  "milled first, the shaft on its wall: the paper's contact counts (#3 touches about 15 shell points at scale 3). "
  "*Control*: constant work as long as the median frame, same run (see above).\n")
w("| algorithm | resolution | grid | pose | mean (µs) | p50 (µs) | p99 (µs) | control p99 (µs) | max (µs) | equivalent rate (kHz) | contacts (min–max) | paper (ms per frame) |")
w("|---|---|---|---|---|---|---|---|---|---|---|---|")
paper = {("LineProxyRenderer", "vertexCount=51"): "1.02 (50 vertices)", ("LineProxyRenderer", "vertexCount=1000"): "1.84 (1,000 vertices)",
         ("SurfacePointRenderer", "slices=20"): "1.05 (184 points)", ("SurfacePointRenderer", "slices=100"): "1.61",
         ("BarbicRenderer", "pointShellScale=1"): "7.87 (72,326 points, 127 Hz)",
         ("BarbicRenderer", "pointShellScale=2"): "1.97 (18,549 points, 507 Hz)",
         ("BarbicRenderer", "pointShellScale=3"): "1.01 (8,399 points, 987 Hz)"}
for r in rates:
    grid = r.get("grid", COARSE)
    w(f"| {r['renderer']} | {r['resolution']} | {grid} | {r.get('pose') or 'gentle'} | {fmt(num(r['mean_us']))} | "
      f"{fmt(num(r['p50_us']))} | {fmt(num(r['p99_us']))} | {fmt(num(r.get('control_p99_us', '')))} | "
      f"{fmt(num(r.get('max_us', '')))} | {fmt(num(r['rate_hz']) / 1e3)} | "
      f"{r.get('min_contacts', '?')}–{r.get('max_contacts', '–')} | "
      f"{paper.get((r['renderer'], r['resolution']), '–') if grid == COARSE and r.get('pose', 'gentle') != 'deep' else '–'} |")
w("\nThe paper ran §8.1 on its 256×256×176 CT grid; the 8×-voxel rows are the same tooth phantom at 512×512×352 "
  "(0.05 mm voxels), where #3's point shell has 4× the points at each scale.\n")

w("## Largest stable stiffness (Z-width)\n")
w("Each renderer's stiffness field (the proxy spring of #1, the penalty spring of #2, the virtual coupling of #3) "
  "raised in √2 steps from 250 N/m; every value must pass the static push, a 0.1 m/s impact and a release in contact "
  "on the closed 1 kHz loop with the simulated hand, under the thresholds of [stability.md](stability.md). The sweep "
  "stops at the first failure. *Felt*: the stiffness the device actually meets on a flat surface (the force "
  "difference between two quasi-static depths over their distance), which makes the methods comparable: #2 shares its "
  "spring among the touching points; #3's coupling sits in series with the contact, and its default (rigidContact) "
  "adds back what the penetration takes, so it feels the coupling's own stiffness. "
  "Colgate & Brown's "
  "bound for a sampled spring, K < 2b/T with b the physical damping, is 2·(B + 1 N·s/m device)/1 ms: 6 kN/m for the "
  "loose grip, 15 kN/m for the measured arm, 22 kN/m for the firm grip.\n")
zmd = optional_text("zwidth.md")
w(zmd if zmd else "Not measured in this run.\n")

w("## The paper's §8.2: the comparison procedure\n")
w("One 40 s real-time run per renderer of `x3d/default.x3d` (`millsim run --renderer R --trajectory "
  "x3d/trajectories/section-8-2.csv --no-graphics`): the simulated hand (HandDevice, the lesson's grip) approaches, "
  "mills a 2.5 mm hole with the button held, leans the shaft 20° against the hole's edge and holds (0–20 s, "
  "*milling*); then, button off, eases the lean and leans back against the wall and holds as still as it can "
  "(20–40 s, *non-milling*). Every renderer at its defaults. The metrics and the scoring rule are "
  "`scripts/score-procedure`'s (its header states them); the paper's Table 1 scored #1/#2/#3 as 8/6/5. "
  "These are real-time runs on a shared host: the closed loop sees the timing, so the per-part figures move between "
  "runs and a score can move by one (re-run `scripts/bench` to see the spread).\n")
for rend in renderers:
    txt = optional_text(f"procedure-{rend}.txt").strip()
    if txt:
        w(f"`{rend}`:\n\n```\n{txt}\n```\n")
pmd = optional_text("procedure.md")
w(pmd if pmd else "Not measured in this run.\n")
rmd = optional_text("procedure-replay.md")
if rmd:
    w("\nThe same procedure in simulated time (`millsim replay`, the same closed-loop hand, every frame exactly "
      "1 ms): the host's timing is out of it, so these scores are bit-reproducible and judge the renderers alone.\n")
    w(rmd)
if pmd:
    for part in ("milling", "non-milling"):
        w(f"\n**{part.capitalize()}** (the paper's Figs. 16–19, {'top' if part == 'milling' else 'bottom'} rows):\n")
        w(" ".join(f"![{part} {k}](images/procedure/{part}/{k}.png)" for k in ("rate", "force", "torque", "shaft")) + "\n")

w("## Stability\n")
w("Closed loop at 1 kHz with the simulated hand (HandDevice), thresholds in [stability.md](stability.md). "
  "minE: the passivity observer as specified (pass: ≥ −1 mJ per 60 s); minEzoh: the exact work of the held wrench "
  "(measured, not judged). p-p: peak-to-peak motion in the last 0.5 s. depth: deepest burr-centre travel past first contact.\n")
w("| renderer | scenario | hand | minE (µJ) | minEzoh (µJ) | p-p (µm) | peak force (N) | depth (mm) | result |")
w("|---|---|---|---|---|---|---|---|---|")
for p in scen:
    res = "pass" if not any(x.startswith("FAIL") for x in p) else next(x for x in p if x.startswith("FAIL"))
    w(f"| {p[0]} | {p[1]} | {p[2]} | {fmt(field(p, 'minE '))} | {fmt(field(p, 'minEzoh '))} | {fmt(field(p, 'p-p '))} | "
      f"{fmt(field(p, 'peak '))} | {fmt(field(p, 'depth '))} | {res} |")
w("\n**Fall-through** (kinematic pass, 8 phases per speed; speeds 0.05–2 m/s):\n")
for l in falls:
    w(f"- {l}")
w("\n**Fuzz** (CI length; the soak runs 10⁶ frames per renderer):\n")
for l in fuzz:
    w(f"- {l}")
if known:
    w("\n**Known issues the suite exposed** (printed, not failed; see stability.md):\n")
    for l in known:
        w(f"- {l[len('KNOWN ISSUE '):]}")

w("\n## Which algorithm to choose when\n")
default_rows = [r for r in allrows if r["resolution"] == "default" and abs(num(r["h_mm"]) - 0.1) < 1e-9]
def best(metric, among=None):
    c = [r for r in default_rows if math.isfinite(num(r[metric])) and (among is None or r["renderer"] in among)]
    return min(c, key=lambda r: num(r[metric]))["renderer"] if c else "–"
# Torque is compared only where it is measured against a shaft contact (the edge scene).
edge_torque = {r["renderer"] for r in acc if r["scene"] == "edge" and r["resolution"] == "default"
               and abs(num(r["h_mm"]) - 0.1) < 1e-9 and math.isfinite(num(r["torque_rms"]))}
phys_all = [r for r in physical_rows if r["scene"] == "all" and r.get("resolution", "default") == "default"
            and abs(num(r["h_mm"]) - 0.1) < 1e-9]
def best_phys(metric, unit=""):
    c = [r for r in phys_all if math.isfinite(num(r[metric]))]
    if not c:
        return "–"
    r = min(c, key=lambda r: num(r[metric]))
    value = num(r[metric]) * (100 if unit == " %" else 1)
    return f"**{r['renderer']}** ({fmt(value)}{unit})"
if phys_all:
    w(f"- **Accuracy against the rigid tool** (h = 0.1 mm, defaults, [accuracy.md](accuracy.md#physical-reference)): "
      f"lowest force error {best_phys('force_rms', ' %')}, force direction {best_phys('dir_rms_deg', '°')}, "
      f"torque {best_phys('torque_rms')}.")
w(f"- **Fidelity to its own law** (h = 0.1 mm, defaults): lowest force error **{best('force_rms')}**; lowest shaft-torque error "
  f"**{best('torque_rms', edge_torque)}** (among {', '.join(sorted(edge_torque)) or 'none'}: the own-law shaft torque of a "
  "coupled tool is not modelled). Each is against the algorithm's *own* law fed with exact geometry (how faithfully it "
  "renders its model), not one physical truth.")
held = [rend for rend in renderers if safe.get(rend) and all(x[2] for x in safe[rend])]
if held:
    w(f"- **Thin walls, fast strokes**: {', '.join('**' + h + '**' for h in held)} held every plate (1, 2, 4 voxels, "
      "1 mm) at every speed tried, up to 2 m/s.")
for rend in renderers:
    sp = safe.get(rend, [])
    if sp and not all(x[2] for x in sp):
        w(f"- {rend} is safe on thin plates only up to {min(num(x[1]) for x in sp):g} m/s, and a hand that pushes "
          "harder than the small force it builds before the midplane goes through at any speed.")
if any("SurfacePointRenderer" in l for l in known):
    w("- **Hard, fast contact** (impacts, pushing > 2.5 N): not SurfacePointRenderer — its force saturates near 2.5 N "
      "and the device sinks; sliding on it also adds energy in proportion to the distance (see Known issues).")
if zwidth:
    felt = {}
    for r in zwidth:
        if r["hand"] == ARM:
            felt[r["renderer"]] = num(r["rendered_at_largest"])
    if felt:
        top = max(felt, key=felt.get)
        w("- **Stiffness headroom** (measured arm's grip): the stiffest stable contact the device meets is "
          + ", ".join(f"{k} {v:.0f} N/m" for k, v in sorted(felt.items())) +
          f" — highest for **{top}**, against Colgate's bound of about 15 kN/m for that grip; every default keeps at "
          "least a twofold margin on every grip (the loose grip is the binding one).")
if procedure:
    totals = {r["algorithm"]: int(r["total"]) for r in procedure}
    order = sorted(totals, key=totals.get)
    w("- **The §8.2 procedure** (simulated hand, 40 s): totals " + ", ".join(f"{k} {totals[k]}" for k in order) +
      " (lower is better; the paper: #1 8, #2 6, #3 5). The simulated hand has no tremor and follows a linear grip, "
      "so the penalty method's direct rendering (#2) loses less here than with the paper's human hand; its shaft is "
      "the device's own and scores best on compactness, as in the paper.")
rr = {r["renderer"]: r for r in rates if r["resolution"] in paper_res.values() and r.get("grid", COARSE) == COARSE}
if rr:
    w("- **Time**: at the paper's resolutions every algorithm needs well under 1 ms per frame on the phantom (p99: "
      + ", ".join(f"{k} {fmt(num(v['p99_us']))} µs" for k, v in sorted(rr.items())) +
      "), also at 8× voxels: pick the resolution from the Pareto plot for the error you need, not for time. Not yet "
      "at micro-CT voxels: at 25 µm a milling frame costs several hundred µs (see Cost against resolution).")
w("- The lines above are generated from the tables by scripts/bench-report.py. Our reading of this run (written by "
  "hand, re-check it when the numbers move): **BarbicRenderer** as the default for a milling simulator — it never "
  "tunnels, renders real shaft torque, keeps the drawn tool on the surface and costs microseconds; "
  "**LineProxyRenderer** when the lowest burr-force error matters and shaft torque and a steady drawn shaft matter "
  "less; **SurfacePointRenderer** only for soft, slow contact, where its direct rendering gives the steadiest shaft.\n")
open(os.path.join(a.docs, "results.md"), "w").write("\n".join(out) + "\n")

# The physical suite's tables go into docs/accuracy.md, between its markers.
if physical:
    path = os.path.join(a.docs, "accuracy.md")
    text = open(path).read()
    begin, end = "<!-- physical:begin (scripts/bench writes this block) -->", "<!-- physical:end -->"
    if begin in text and end in text:
        text = text[:text.index(begin) + len(begin)] + "\n" + physical.strip() + "\n" + text[text.index(end):]
        open(path, "w").write(text)
    else:
        print("bench-report: docs/accuracy.md has no physical markers; its tables were not updated")
