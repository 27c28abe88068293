#!/usr/bin/env python3
"""Reference values for plugins.shift.manufactured_current_matches_sympy: the momentum density J^i that
makes beta_exact of manufactured.hpp an exact solution of eq. mindist_hat (phi = chi, no puncture),
differentiated symbolically. Run: /usr/bin/python3 manufactured_sympy.py"""
import sympy as sp
x,y,z=sp.symbols('x y z',real=True)
X=[x,y,z]
R=sp.Integer(1); sigma=sp.Rational(9,10)
s=x**2+y**2+z**2
def G(p,w): return sp.exp(-((x-p[0])**2+(y-p[1])**2+(z-p[2])**2)/w**2)
xi2=s/R**2
c1=[693,-1155,1386,-990,385,-63]
F1_in=sum(sp.Rational(c,256)*xi2**k for k,c in enumerate(c1))/R
F2_in=sum(c*xi2**k for k,c in enumerate([6,-15,20,-15,6,-1]))/R**2
F1_out=1/sp.sqrt(s); F2_out=1/s
r=sp.Rational
chi=1+r(2,10)*G((r(3,10),r(-2,10),0),r(8,10))
eta=r(9,10)-r(15,100)*G((r(-25,100),r(15,100),0),r(7,10))
g=G((r(1,10),r(2,10),0),r(7,10))
axx=(r(24,10)+r(16,10)*x)*g; ayy=(r(-8,10)+r(8,10)*y)*g; azz=-(axx+ayy)
axy=r(12,10)*g; axz=r(16,10)*z*g; ayz=r(-8,10)*z*g
A=sp.Matrix([[axx,axy,axz],[axy,ayy,ayz],[axz,ayz,azz]])
rho0=r(1,10)+r(1,10)*G((r(2,10),r(1,10),0),r(6,10))
h=1+2*rho0
def beta(F1,F2):
    return [r(3,100)*F1+r(2,100)*y*F2, r(-25,1000)*F1+r(25,1000)*x*F2, r(2,100)*z*F2]
def Jreq(F1,F2,pt):
    b=beta(F1,F2)
    div=sum(sp.diff(b[k],X[k]) for k in range(3))
    phi=chi; alpha=eta/phi
    dphi=[sp.diff(phi,v) for v in X]
    dal=[(sp.diff(eta,X[j])-alpha*dphi[j])/phi for j in range(3)]
    out=[]
    for i in range(3):
        P=sum(sp.diff(b[i],v,2) for v in X)+sp.diff(div,X[i])/3
        sh=sum((sp.diff(b[i],X[j])+sp.diff(b[j],X[i]))*dphi[j] for j in range(3))-r(2,3)*dphi[i]*div
        R0=-6/phi*sh+2*phi**-6*sum(A[i,j]*dal[j] for j in range(3))
        J=(P-R0)/(16*sp.pi*sigma**2*alpha*phi**4)
        out.append(J)
    sub={x:pt[0],y:pt[1],z:pt[2]}
    vals=[sp.N(e.subs(sub),20) for e in out]
    bv=[sp.N(e.subs(sub),20) for e in b]
    return vals,bv,[sp.N(e.subs(sub),20) for e in (phi,eta,rho0)]
for pt,inside in [((r(3,10),r(-4,10),r(2,10)),True),((r(9,10),r(7,10),r(-5,10)),False),((r(-15,10),r(12,10),r(8,10)),False)]:
    rr=sp.sqrt(sum(c**2 for c in pt))
    assert (rr<1)==inside
    J,b,o=Jreq(F1_in,F2_in,pt) if inside else Jreq(F1_out,F2_out,pt)
    print(pt, float(rr)); print(' J',[str(v) for v in J]); print(' beta',[str(v) for v in b]); print(' phi eta rho0',[float(v) for v in o])
