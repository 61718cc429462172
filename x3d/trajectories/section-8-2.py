#!/usr/bin/python3
"""Writes x3d/trajectories/section-8-2.csv: the paper's section 8.2 procedure as HandDevice targets."""
import os
import math
def pose(t):
    if t<=2: return 14e-3+(9.5e-3-14e-3)*t/2, 0, 0
    if t<=10: return 9.5e-3+(7.0e-3-9.5e-3)*(t-2)/8, 0, 1
    if t<=14: return 7.0e-3, 20*(t-10)/4, 1
    if t<20: return 7.0e-3, 20, 1
    if t<=21: return 7.0e-3-2.0e-3*(t-20), 20, 0
    if t<=23: return 5.0e-3, 20-10*(t-21)/2, 0
    if t<=26: return 5.0e-3, 10+10*(t-23)/3, 0
    return 5.0e-3, 20, 0
out=["# The paper's section 8.2 comparison procedure, scripted for HandDevice (40 s, one run).",
"# Milling part (0-20 s): approach the occlusal surface, mill a 2.5 mm hole with the button held, lean the",
"# shaft 20 degrees so it meets the hole's edge, keep milling and hold. Non-milling part (20-40 s): button off,",
"# press 2 mm past the bottom of the milled hole, ease the lean to 10 degrees and back against the wall, then",
"# hold as still as possible. The simulated hand follows these targets through its grip springs.",
"t,x,y,z,qw,qx,qy,qz,button"]
ts=sorted(set([i*0.25 for i in range(0,161)]+[19.999]))
for t in ts:
    y,a,b=pose(t)
    h=math.radians(a)/2
    out.append(f"{t:g},0,{y:.6g},0,{math.cos(h):.6g},0,0,{-math.sin(h):.6g},{b}")
open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "section-8-2.csv"), "w").write("\n".join(out)+"\n")
