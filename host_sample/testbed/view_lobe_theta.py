#!/usr/bin/env python3
"""The turn of the view direction per frame on rrc-sample's mirror sphere.

theta = the angle between P - C(t) and P - C(t - 1/30) for points P of the
sphere's half facing the camera (centre (-3.2, 1.3, 5.6), radius 1.3: Scene::sphere,
set by Scene::make in host_sample/testbed/scene.cpp) along the default camera path (Scene::camera in
host_sample/testbed/scene.cpp, camera_speed 1, --fps 30), frames 1..59.
docs/measurements/PERFORMANCE.md, "The view-dependent history (env): the rule, measured before building it",
uses its range to find the lobes whose age cap floor(lobe/theta) is the same
at every pixel and frame.

    python3 host_sample/testbed/view_lobe_theta.py
"""
import math
def eye(t):
    a=1.95-0.35*t; r=15.0
    return (r*math.cos(a),4.2+0.4*t,r*math.sin(a))
sub=lambda a,b:tuple(x-y for x,y in zip(a,b))
dot=lambda a,b:sum(x*y for x,y in zip(a,b))
nrm=lambda a:math.sqrt(dot(a,a))
def cross(a,b): return (a[1]*b[2]-a[2]*b[1],a[2]*b[0]-a[0]*b[2],a[0]*b[1]-a[1]*b[0])
def sc(a,s): return tuple(x*s for x in a)
def add(*v): return tuple(sum(x) for x in zip(*v))
th=[]
S=(-3.2,1.3,5.6); R=1.3
for i in range(1,60):
    c,p=eye(i/30),eye((i-1)/30)
    d=sc(sub(S,c),1/nrm(sub(S,c)))
    a=cross(d,(0,1,0)); a=sc(a,1/nrm(a)); b=cross(a,d)
    for u in [x/10 for x in range(-10,11)]:
      for v in [x/10 for x in range(-10,11)]:
        if u*u+v*v>1: continue
        n=add(sc(d,-math.sqrt(max(0,1-u*u-v*v))),sc(a,u),sc(b,v))
        P=add(S,sc(n,R)); x=sub(P,c); y=sub(P,p)
        th.append(math.acos(min(1,dot(x,y)/nrm(x)/nrm(y))))
print("theta min %.5f mean %.5f max %.5f rad" % (min(th),sum(th)/len(th),max(th)))
# floor(lobe/theta) = N at every pixel and frame iff N*max <= lobe < (N+1)*min.
lo, hi = min(th), max(th)
for N in range(1, 12):
    if N * hi < (N + 1) * lo:
        print("age cap %2d (lambda_eff <= %.4f): lobe in [%.4f, %.4f) rad" % (N, N / (N + 1.0), N * hi, (N + 1) * lo))
