/* A plain-C port of the Leuven and LuGre displacement-driven simulation of
 * leuven_friction.model.kernels (run_displacement without scales, piecewise-linear transition
 * curve): the same passes, the same Newton solve with the same tolerance, the same memory
 * mechanisms, operation for operation, so the output is expected to be bit-identical.
 * It exists only as the benchmark's reference for what the compiled Python kernel could reach.
 * Build: cc -O2 -shared -fPIC leuven_step.c -o leuven_step.so -lm
 */
#include <math.h>

/* layout: leuven_friction.model.layout (checked by the benchmark before timing) */
enum { P_SP = 0, P_N = 10, P_NINT = 11, P_SIGMA1 = 12, P_SIGMA0 = 13, P_REVTOL = 14, NEG = 5 };
enum { S_Z, S_FB, S_DIR, S_NMIN, S_NMAX, S_REVERSALS, S_CLOSINGS, S_RESETS, S_DEPTH, S_DROPPED, S_SV, HEADER };
enum { LEUVEN = 0, LUGRE = 1 };
#define RESET_TOL 1e-9

typedef struct { const double *z, *F; long n; } curve;

static double pmin(double a, double b) { return b < a ? b : a; } /* Python's min(a, b) */
static double pmax(double a, double b) { return b > a ? b : a; } /* Python's max(a, b) */

static double stribeck(const double *p, double v, double side) {
    int o = side > 0 ? P_SP : NEG;
    double Fs = p[o], Fc = p[o + 1], vs = p[o + 2], dl = p[o + 3];
    if (v == 0.0) return Fs;
    double u = fabs(v / vs);
    double e = dl == 0.5 ? sqrt(u) : pow(u, dl);
    return Fc + (Fs - Fc) * exp(-e);
}

static void stribeck_pass(const double *p, const double *t, const double *x, long n, double *V, double *S) {
    V[0] = 0.0;
    double vlast = 0.0, slast = p[P_SP];
    for (long k = 1; k < n; k++) {
        double v = (x[k] - x[k - 1]) / (t[k] - t[k - 1]);
        V[k] = v;
        if (v != vlast) {
            vlast = v;
            slast = stribeck(p, v, v > 0.0 ? 1.0 : -1.0);
        }
        S[k] = slast;
    }
}

static long segment(const double *knots, long n, double a) {
    long i = 1, last = n - 1;
    while (i < last && a > knots[i]) i++;
    return i;
}

static double odd_interp(const double *xk, const double *yk, long n, double u) {
    double a = fabs(u);
    long i = segment(xk, n, a);
    double y = yk[i - 1] + (yk[i] - yk[i - 1]) / (xk[i] - xk[i - 1]) * (a - xk[i - 1]);
    return u >= 0.0 ? y : -y;
}

static double Fd(const curve *c, double z) { return odd_interp(c->z, c->F, c->n, z); }
static double Fd_inv(const curve *c, double F) { return odd_interp(c->F, c->z, c->n, F); }
static double Fd_slope(const curve *c, double z) {
    long i = segment(c->z, c->n, fabs(z));
    return (c->F[i] - c->F[i - 1]) / (c->z[i] - c->z[i - 1]);
}

static void drop_oldest_internal_pair(double *st, long cap) {
    long nmin = (long)st[S_NMIN], nmax = (long)st[S_NMAX];
    if (nmin >= 2) {
        for (long i = 1; i < nmin - 1; i++) st[HEADER + i] = st[HEADER + i + 1];
        st[S_NMIN] = nmin - 1;
    }
    if (nmax >= 2) {
        for (long i = 1; i < nmax - 1; i++) st[HEADER + cap + i] = st[HEADER + cap + i + 1];
        st[S_NMAX] = nmax - 1;
    }
    st[S_DROPPED] += 1;
}

static void velocity_reversal(double *st, long cap, const double *p, const curve *c, double side, double kap) {
    double d = st[S_DIR];
    double fd = Fd(c, kap * st[S_Z]);
    double fh = st[S_FB] + fd;
    long nmin = (long)st[S_NMIN], nmax = (long)st[S_NMAX];
    if (d != 0.0 && fabs(fd) <= p[P_REVTOL]) {
        if (d > 0.0 && nmin >= 2) {
            st[S_NMIN] = nmin - 1;
            double fb = st[HEADER + cap + nmax - 1];
            st[S_FB] = fb;
            st[S_Z] = Fd_inv(c, fh - fb) / kap;
            st[S_DIR] = side;
            return;
        }
        if (d < 0.0 && nmax >= 2) {
            st[S_NMAX] = nmax - 1;
            double fb = st[HEADER + nmin - 1];
            st[S_FB] = fb;
            st[S_Z] = Fd_inv(c, fh - fb) / kap;
            st[S_DIR] = side;
            return;
        }
    }
    if (side > 0.0) {
        if (nmin >= cap) { drop_oldest_internal_pair(st, cap); nmin = (long)st[S_NMIN]; }
        st[HEADER + nmin] = fh;
        st[S_NMIN] = nmin + 1;
    } else {
        if (nmax >= cap) { drop_oldest_internal_pair(st, cap); nmax = (long)st[S_NMAX]; }
        st[HEADER + cap + nmax] = fh;
        st[S_NMAX] = nmax + 1;
    }
    double depth = pmax(st[S_NMIN], st[S_NMAX]);
    if (depth > st[S_DEPTH]) st[S_DEPTH] = depth;
    st[S_FB] = fh;
    st[S_Z] = 0.0;
    st[S_DIR] = side;
    st[S_REVERSALS] += 1;
}

static void close_internal_loops(double *st, long cap, const curve *c, double fh, double kap) {
    for (;;) {
        long nmin = (long)st[S_NMIN], nmax = (long)st[S_NMAX];
        double fb;
        if (nmin < 2 || nmax < 2) return;
        if (st[S_DIR] > 0.0 && fh >= st[HEADER + cap + nmax - 1]) fb = st[HEADER + nmin - 2];
        else if (st[S_DIR] < 0.0 && fh <= st[HEADER + nmin - 1]) fb = st[HEADER + cap + nmax - 2];
        else return;
        st[S_NMIN] = nmin - 1;
        st[S_NMAX] = nmax - 1;
        st[S_FB] = fb;
        st[S_Z] = Fd_inv(c, fh - fb) / kap;
        st[S_CLOSINGS] += 1;
    }
}

static void reset_to_outer_loop(double *st, long cap, const double *p, const curve *c, double side, double fh, double kap) {
    double fb = side > 0.0 ? p[P_SP + 5] : p[P_SP];
    if (st[S_NMIN] == 1.0 && st[S_NMAX] == 1.0 && st[S_FB] == fb) return;
    st[HEADER] = p[P_SP + 5];
    st[HEADER + cap] = p[P_SP];
    st[S_NMIN] = 1.0;
    st[S_NMAX] = 1.0;
    st[S_FB] = fb;
    st[S_Z] = Fd_inv(c, fh - fb) / kap;
    st[S_DIR] = side;
    st[S_RESETS] += 1;
}

static double abs_pow(double a, const double *p) {
    long ni = (long)p[P_NINT];
    if (ni == 7) { double a3 = a * a * a; return a3 * a3; }
    if (ni > 0) {
        long m = ni - 1;
        double r = 1.0, b = a;
        while (m > 0) { if (m & 1) r *= b; b *= b; m >>= 1; }
        return r;
    }
    return pow(a, p[P_N] - 1.0);
}

static double solve_state_equation(const double *p, const curve *c, double z0, double fd0, double dx, double D, double kap) {
    double n = p[P_N];
    double r0 = fd0 / D;
    double rn0 = abs_pow(fabs(r0), p);
    double ph0 = rn0 * r0;
    int below = ph0 < 1.0;
    double g0 = -dx * (1.0 - ph0);
    double dg0 = 1.0 + dx * n * rn0 * kap * Fd_slope(c, kap * z0) / D;
    double z = z0 - g0 / dg0;
    double lo, hi;
    if (g0 < 0.0) { lo = z0; hi = INFINITY; } else { lo = -INFINITY; hi = z0; }
    if (below) { if (dx > 0.0) hi = z0 + dx; else lo = z0 + dx; }
    double tol = 1e-7 * fabs(dx) + 1e-300;
    int far_known = below;
    for (int it = 0; it < 60; it++) {
        double fd = Fd(c, kap * z);
        double r = fd / D;
        double rn1 = abs_pow(fabs(r), p);
        double g = z - z0 - dx * (1.0 - rn1 * r);
        if (g == 0.0) break;
        if (g > 0.0) hi = pmin(hi, z); else lo = pmax(lo, z);
        double dg = 1.0 + dx * n * rn1 * kap * Fd_slope(c, kap * z) / D;
        double zn = z - g / dg;
        if (fabs(zn - z) <= tol) { z = zn; break; }
        if (!far_known) {
            far_known = 1;
            double zs = Fd_inv(c, D) / kap;
            if (dx > 0.0) lo = pmax(lo, zs); else hi = pmin(hi, zs);
        }
        if (zn <= lo || zn >= hi) zn = 0.5 * (lo + hi);
        z = zn;
    }
    return z;
}

/* model: 0 Leuven, 1 LuGre; st: a state vector from initial_state (updated in place). */
void run_displacement(long model, const double *p, const double *tz, const double *tF, long nknots,
                      double *st, long nst, const double *t, const double *x, long n,
                      double *F, double *Fh, double *Z, double *V) {
    curve c = {tz, tF, nknots};
    long cap = (nst - HEADER) / 2;
    const double kap = 1.0, sc = 1.0;
    stribeck_pass(p, t, x, n, V, Fh);
    double sig1 = p[P_SIGMA1], c_pos = p[P_SP + 4], c_neg = p[NEG + 4];
    double fh = model == LEUVEN ? st[S_FB] + Fd(&c, kap * st[S_Z]) : kap * p[P_SIGMA0] * st[S_Z];
    F[0] = sc * fh;
    Fh[0] = sc * fh;
    Z[0] = st[S_Z];
    for (long k = 1; k < n; k++) {
        double v = V[k];
        if (v == 0.0) {
            F[k] = sc * fh;
            Fh[k] = sc * fh;
        } else {
            double side = v > 0.0 ? 1.0 : -1.0;
            double dx = x[k] - x[k - 1];
            double s = Fh[k], dz;
            st[S_SV] = s;
            if (model == LEUVEN) {
                if (side != st[S_DIR]) velocity_reversal(st, cap, p, &c, side, kap);
                double fb = st[S_FB], z = st[S_Z];
                double D = s - fb;
                double fd = Fd(&c, kap * z);
                if (side * D <= 0.0 || fd / D >= 1.0 - RESET_TOL) {
                    reset_to_outer_loop(st, cap, p, &c, side, fb + fd, kap);
                    fb = st[S_FB];
                    z = st[S_Z];
                    D = s - fb;
                    fd = Fd(&c, kap * z);
                }
                double z1 = solve_state_equation(p, &c, z, fd, dx, D, kap);
                st[S_Z] = z1;
                fh = fb + Fd(&c, kap * z1);
                if (st[S_NMIN] >= 2.0 && st[S_NMAX] >= 2.0) close_internal_loops(st, cap, &c, fh, kap);
                dz = z1 - z;
            } else {
                double z0 = st[S_Z];
                double z1 = (z0 + dx) / (1.0 + fabs(dx) * kap * p[P_SIGMA0] / fabs(s));
                st[S_Z] = z1;
                if (side != st[S_DIR]) { st[S_REVERSALS] += 1; st[S_DIR] = side; }
                dz = z1 - z0;
                fh = kap * p[P_SIGMA0] * st[S_Z];
            }
            F[k] = sc * (fh + sig1 * dz / (t[k] - t[k - 1]) + (side > 0.0 ? c_pos : c_neg) * v);
            Fh[k] = sc * fh;
        }
        Z[k] = st[S_Z];
    }
}
