/* The simulated box's exact pressure solve in compiled code (issue 50, item 4).
 *
 * The same arithmetic, in the same order, as the NumPy reference in softpad.sim._pneumatics
 * (ChamberBank._solve, its first loop: Newton's method from the previous pressure, at most six
 * steps) with the tabulated characteristic's interpolation along the pressure
 * (softpad.sim._characteristic.TabulatedCharacteristic._along_pressure, the load columns
 * cached by the caller): every operation is one IEEE-754 double operation (+, -, *, /, fabs,
 * comparisons), which NumPy's element-wise loops compute identically, so the results are the
 * same bits (tests/box/test_fastsim.py checks them). Built with -ffp-contract=off: no fused
 * multiply-add may merge two roundings into one.
 *
 * No NumPy headers: arrays come in through the buffer protocol (float64; the 1-D ones
 * C-contiguous, the tables (pressures x modules) with any strides), and results are written
 * into arrays the caller allocated.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include <math.h>
#include <string.h>

/* softpad.sim._pneumatics.SETTLED_PA: a channel this close to its equilibrium is settled. */
#define SETTLED_PA 1e-3

typedef struct {
    Py_buffer view;
    int held;
} Buf;

/* Take a C-contiguous float64 buffer of exactly n elements (n < 0: any length); None when
 * allow_none. Returns 0, or -1 with an exception set. */
static int take(PyObject *obj, Buf *b, Py_ssize_t n, int writable, int allow_none,
                const char *what)
{
    b->held = 0;
    if (obj == Py_None && allow_none)
        return 0;
    int flags = PyBUF_C_CONTIGUOUS | PyBUF_FORMAT | (writable ? PyBUF_WRITABLE : 0);
    if (PyObject_GetBuffer(obj, &b->view, flags) < 0)
        return -1;
    b->held = 1;
    const char *f = b->view.format;
    if (b->view.itemsize != 8 || f == NULL || !(f[0] == 'd' || (f[0] == '<' && f[1] == 'd'))) {
        PyErr_Format(PyExc_TypeError, "%s must be a float64 array", what);
        return -1;
    }
    if (n >= 0 && b->view.len != n * 8) {
        PyErr_Format(PyExc_ValueError, "%s must have %zd elements, got %zd", what, n,
                     b->view.len / 8);
        return -1;
    }
    return 0;
}

/* Take a 2-D float64 buffer of shape (rows, cols) (-1: any), any strides (multiples of 8). */
static int take2(PyObject *obj, Buf *b, Py_ssize_t rows, Py_ssize_t cols, const char *what)
{
    b->held = 0;
    if (PyObject_GetBuffer(obj, &b->view, PyBUF_STRIDES | PyBUF_FORMAT) < 0)
        return -1;
    b->held = 1;
    const char *f = b->view.format;
    Py_buffer *v = &b->view;
    if (v->itemsize != 8 || f == NULL || !(f[0] == 'd' || (f[0] == '<' && f[1] == 'd'))) {
        PyErr_Format(PyExc_TypeError, "%s must be a float64 array", what);
        return -1;
    }
    if (v->ndim != 2 || (rows >= 0 && v->shape[0] != rows) || (cols >= 0 && v->shape[1] != cols) ||
        v->strides[0] % 8 ||
        v->strides[1] % 8) {
        PyErr_Format(PyExc_ValueError, "%s must have shape (%zd, %zd)", what, rows, cols);
        return -1;
    }
    return 0;
}

static void release(Buf *bufs, int k)
{
    for (int i = 0; i < k; i++)
        if (bufs[i].held)
            PyBuffer_Release(&bufs[i].view);
}

static double *data(Buf *b) { return b->held ? (double *)b->view.buf : NULL; }

/* Number of grid values <= x (numpy.searchsorted(grid, x, side="right") for finite x). */
static Py_ssize_t count_le(const double *grid, Py_ssize_t n, double x)
{
    Py_ssize_t lo = 0, hi = n;
    while (lo < hi) {
        Py_ssize_t mid = lo + ((hi - lo) >> 1);
        if (grid[mid] <= x)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

typedef struct {
    const double *cols, *slopes, *grid, *drop, *creep;
    Py_ssize_t m, np;
    Py_ssize_t c0, c1, s0, s1; /* strides of cols and slopes, in elements */
} Table;

static Table table(Buf *cols, Buf *slopes, Buf *grid, Buf *drop, Buf *creep, Py_ssize_t m)
{
    Table t = {data(cols), data(slopes), data(grid), data(drop), data(creep), m,
               grid->view.len / 8,
               cols->view.strides[0] / 8, cols->view.strides[1] / 8,
               slopes->view.strides[0] / 8, slopes->view.strides[1] / 8};
    return t;
}

/* V (creep added where given) and dV/dp of module j at gauge pressure p. */
static void volume_and_slope(const Table *t, Py_ssize_t j, double p, double *v, double *dv)
{
    if (t->drop)
        p = p - t->drop[j];
    double g0 = t->grid[0];
    double pc = p >= g0 ? p : g0; /* finite inputs: numpy.maximum's value */
    Py_ssize_t i = count_le(t->grid, t->np, pc) - 1;
    if (i > t->np - 2)
        i = t->np - 2;
    double slope = t->slopes[i * t->s0 + j * t->s1];
    double value = t->cols[i * t->c0 + j * t->c1] + slope * (pc - t->grid[i]);
    *v = t->creep ? value + t->creep[j] : value;
    *dv = p >= g0 ? slope : 0.0;
}

static int finite_all(const double *x, Py_ssize_t n)
{
    for (Py_ssize_t i = 0; i < n; i++)
        if (!isfinite(x[i]))
            return 0;
    return 1;
}

/* solve(p, amount, cols, slopes, grid, drop, creep, patm, vt, p_out, dn_dp_out) -> bool */
static PyObject *solve(PyObject *self, PyObject *args)
{
    PyObject *o[9];
    double patm, vt;
    if (!PyArg_ParseTuple(args, "OOOOOOOddOO", &o[0], &o[1], &o[2], &o[3], &o[4], &o[5], &o[6],
                          &patm, &vt, &o[7], &o[8]))
        return NULL;
    Buf b[9];
    memset(b, 0, sizeof b);
    PyObject *result = NULL;
    if (take(o[0], &b[0], -1, 0, 0, "p") < 0)
        goto done;
    Py_ssize_t m = b[0].view.len / 8;
    if (take(o[1], &b[1], m, 0, 0, "amount") < 0 || take(o[4], &b[4], -1, 0, 0, "grid") < 0)
        goto done;
    Py_ssize_t np_ = b[4].view.len / 8;
    if (np_ < 2) {
        PyErr_SetString(PyExc_ValueError, "grid must have at least 2 pressures");
        goto done;
    }
    if (take2(o[2], &b[2], np_, m, "cols") < 0 || take2(o[3], &b[3], np_ - 1, m, "slopes") < 0 ||
        take(o[5], &b[5], m, 0, 1, "drop") < 0 || take(o[6], &b[6], m, 0, 1, "creep") < 0 ||
        take(o[7], &b[7], m, 1, 0, "p_out") < 0 || take(o[8], &b[8], m, 1, 0, "dn_dp_out") < 0)
        goto done;
    Table t = table(&b[2], &b[3], &b[4], &b[5], &b[6], m);
    const double *p0 = data(&b[0]), *n = data(&b[1]);
    double *p = data(&b[7]), *dn = data(&b[8]);
    int ok = finite_all(p0, m) && finite_all(n, m) && isfinite(patm) && isfinite(vt) &&
             (t.drop == NULL || finite_all(t.drop, m)) && (t.creep == NULL || finite_all(t.creep, m));
    int converged = 0;
    if (ok) {
        memcpy(p, p0, m * sizeof(double));
        for (int it = 0; it < 6 && !converged; it++) {
            double biggest = 0.0;
            int finite = 1;
            for (Py_ssize_t j = 0; j < m; j++) {
                double v, dv;
                volume_and_slope(&t, j, p[j], &v, &dv);
                double d = (v + vt) + (patm + p[j]) * dv;
                double step = ((patm + p[j]) * (v + vt) - n[j]) / d;
                p[j] = p[j] - step;
                dn[j] = d;
                double a = fabs(step);
                if (!isfinite(a))
                    finite = 0;
                else if (a > biggest)
                    biggest = a;
            }
            if (!finite)
                break; /* NaN or infinity: left to the reference */
            converged = biggest < 1e-2;
        }
    }
    result = PyBool_FromLong(converged);
done:
    release(b, 9);
    return result;
}

/* interp(p, cols, slopes, grid, drop, out): the value of the tabulated column at each p. */
static PyObject *interp(PyObject *self, PyObject *args)
{
    PyObject *o[6];
    if (!PyArg_ParseTuple(args, "OOOOOO", &o[0], &o[1], &o[2], &o[3], &o[4], &o[5]))
        return NULL;
    Buf b[6];
    memset(b, 0, sizeof b);
    PyObject *result = NULL;
    if (take(o[0], &b[0], -1, 0, 0, "p") < 0 || take(o[3], &b[3], -1, 0, 0, "grid") < 0)
        goto done;
    Py_ssize_t m = b[0].view.len / 8, np_ = b[3].view.len / 8;
    if (np_ < 2) {
        PyErr_SetString(PyExc_ValueError, "grid must have at least 2 pressures");
        goto done;
    }
    if (take2(o[1], &b[1], np_, m, "cols") < 0 || take2(o[2], &b[2], np_ - 1, m, "slopes") < 0 ||
        take(o[4], &b[4], m, 0, 1, "drop") < 0 || take(o[5], &b[5], m, 1, 0, "out") < 0)
        goto done;
    Buf none = {.held = 0};
    Table t = table(&b[1], &b[2], &b[3], &b[4], &none, m);
    const double *p = data(&b[0]);
    double *out = data(&b[5]);
    int ok = finite_all(p, m) && (t.drop == NULL || finite_all(t.drop, m));
    if (ok)
        for (Py_ssize_t j = 0; j < m; j++) {
            double dv;
            volume_and_slope(&t, j, p[j], &out[j], &dv);
        }
    result = PyBool_FromLong(ok);
done:
    release(b, 6);
    return result;
}

/* g(x) = x / sqrt(|x| + p_lam): the orifice law's pressure dependence. */
static double orifice(double x, double lam_pa) { return x / sqrt(fabs(x) + lam_pa); }

/* relax(p, eq, flowing, a_in, a_out, dn_dp, supply, laminar, k, mode, lam_out, p_eq_out)
 * -> bool: ChamberBank._relaxation (mode 1: no outflow, 2: no inflow, 0: both; flowing None:
 * every channel flows). False: an input was not finite (nothing written). */
static PyObject *relax(PyObject *self, PyObject *args)
{
    PyObject *o[8];
    double supply, lam_pa, k;
    int mode;
    if (!PyArg_ParseTuple(args, "OOOOOOdddiOO", &o[0], &o[1], &o[2], &o[3], &o[4], &o[5], &supply,
                          &lam_pa, &k, &mode, &o[6], &o[7]))
        return NULL;
    Buf b[8];
    memset(b, 0, sizeof b);
    PyObject *result = NULL;
    if (take(o[0], &b[0], -1, 0, 0, "p") < 0)
        goto done;
    Py_ssize_t m = b[0].view.len / 8;
    if (take(o[1], &b[1], m, 0, 0, "eq") < 0 || take(o[3], &b[3], m, 0, 0, "a_in") < 0 ||
        take(o[4], &b[4], m, 0, 0, "a_out") < 0 || take(o[5], &b[5], m, 0, 0, "dn_dp") < 0 ||
        take(o[6], &b[6], m, 1, 0, "lam_out") < 0 || take(o[7], &b[7], m, 1, 0, "p_eq_out") < 0)
        goto done;
    const unsigned char *flowing = NULL;
    if (o[2] != Py_None) { /* a bool array */
        if (PyObject_GetBuffer(o[2], &b[2].view, PyBUF_C_CONTIGUOUS) < 0)
            goto done;
        b[2].held = 1;
        if (b[2].view.len != m || b[2].view.itemsize != 1) {
            PyErr_SetString(PyExc_ValueError, "flowing must be a bool array of the modules");
            goto done;
        }
        flowing = (const unsigned char *)b[2].view.buf;
    }
    const double *p = data(&b[0]), *eq = data(&b[1]), *a_in = data(&b[3]), *a_out = data(&b[4]);
    const double *dn = data(&b[5]);
    double *lam = data(&b[6]), *p_eq = data(&b[7]);
    int ok = finite_all(p, m) && finite_all(eq, m) && finite_all(a_in, m) &&
             finite_all(a_out, m) && finite_all(dn, m) && isfinite(supply) && isfinite(k);
    for (Py_ssize_t j = 0; ok && j < m; j++) {
        double pe = (flowing == NULL || flowing[j]) ? eq[j] : p[j];
        double d = p[j] - pe;
        double flow;
        if (mode == 1)
            flow = k * (a_in[j] * orifice(supply - p[j], lam_pa));
        else if (mode == 2)
            flow = k * -(a_out[j] * orifice(p[j], lam_pa));
        else
            flow = k * (a_in[j] * orifice(supply - p[j], lam_pa) - a_out[j] * orifice(p[j], lam_pa));
        int far = fabs(d) > SETTLED_PA;
        double r = -flow / (far ? d : 1.0) / dn[j];
        r = r >= 0.0 ? r : 0.0; /* numpy.maximum(r, 0.0) for a number r: r (or a zero) */
        lam[j] = far ? r : 0.0;
        p_eq[j] = pe;
    }
    result = PyBool_FromLong(ok);
done:
    release(b, 8);
    return result;
}

/* ramp(p0, p_eq, decay, lam, resolve_pa, path) -> rows: the stretch's true pressures
 * p_eq + (p0 - p_eq) decay (decay = exp(-lam t), rows of steps, computed by NumPy: its exp
 * is not the C library's) into the first m columns of path, and the rows to keep: as
 * _start_stretch, the binary search of resolve_pa in the largest move of a rising channel
 * (lam > 0) from p0 along the rows (at least one row; all of them when there is one). */
static PyObject *ramp(PyObject *self, PyObject *args)
{
    PyObject *o[5];
    double resolve_pa;
    if (!PyArg_ParseTuple(args, "OOOOdO", &o[0], &o[1], &o[2], &o[3], &resolve_pa, &o[4]))
        return NULL;
    Buf b[5];
    memset(b, 0, sizeof b);
    PyObject *result = NULL;
    if (take(o[0], &b[0], -1, 0, 0, "p0") < 0 || take(o[4], &b[4], -1, 1, 0, "path") < 0)
        goto done;
    Py_ssize_t m = b[0].view.len / 8;
    if (take(o[1], &b[1], m, 0, 0, "p_eq") < 0 || take(o[3], &b[3], m, 0, 0, "lam") < 0 ||
        take(o[2], &b[2], -1, 0, 0, "decay") < 0)
        goto done;
    Py_ssize_t rows = b[2].view.len / 8 / (m ? m : 1);
    Py_buffer *pv = &b[4].view;
    if (m == 0 || rows < 1 || b[2].view.len != rows * m * 8 || pv->ndim != 2 ||
        pv->shape[0] < rows || pv->shape[1] < m) {
        PyErr_SetString(PyExc_ValueError, "ramp: decay must be (rows, m), path (>= rows, >= m)");
        goto done;
    }
    const double *p0 = data(&b[0]), *pe = data(&b[1]), *dec = data(&b[2]), *lam = data(&b[3]);
    double *path = data(&b[4]);
    Py_ssize_t width = pv->shape[1], keep = rows;
    double *moved = PyMem_Malloc(rows * sizeof(double));
    if (moved == NULL) {
        PyErr_NoMemory();
        goto done;
    }
    for (Py_ssize_t r = 0; r < rows; r++) {
        double most = 0.0;
        for (Py_ssize_t j = 0; j < m; j++) {
            double a = pe[j] + (p0[j] - pe[j]) * dec[r * m + j];
            path[r * width + j] = a;
            double d = fabs(a - p0[j]);
            if (lam[j] > 0 && d > most)
                most = d;
        }
        moved[r] = most;
    }
    if (rows > 1) { /* numpy.searchsorted(moved, resolve_pa, side="right"), at least 1 */
        keep = count_le(moved, rows, resolve_pa);
        keep = keep > 1 ? keep : 1;
    }
    PyMem_Free(moved);
    result = PyLong_FromSsize_t(keep);
done:
    release(b, 5);
    return result;
}

/* crosses(p, p_start, p_eq) -> bool: whether any channel's (p - p_eq) (p_start - p_eq) < 0
 * (ChamberBank._no_crossing's test: the solve landed past the stretch's equilibrium). */
static PyObject *crosses(PyObject *self, PyObject *args)
{
    PyObject *o[3];
    if (!PyArg_ParseTuple(args, "OOO", &o[0], &o[1], &o[2]))
        return NULL;
    Buf b[3];
    memset(b, 0, sizeof b);
    PyObject *result = NULL;
    if (take(o[0], &b[0], -1, 0, 0, "p") < 0)
        goto done;
    Py_ssize_t m = b[0].view.len / 8;
    if (take(o[1], &b[1], m, 0, 0, "p_start") < 0 || take(o[2], &b[2], m, 0, 0, "p_eq") < 0)
        goto done;
    const double *p = data(&b[0]), *ps = data(&b[1]), *pe = data(&b[2]);
    int any = 0;
    for (Py_ssize_t j = 0; j < m; j++)
        any |= (p[j] - pe[j]) * (ps[j] - pe[j]) < 0;
    result = PyBool_FromLong(any);
done:
    release(b, 3);
    return result;
}

/* readings(true, noise, q, inv_q, lo, hi, out) -> (lows, highs) or None: the sensors'
 * readings of rows of true pressures with their rows of noise, as SensorBank._quantise
 * (true + noise, times 1/q, rounded half to even, times q, clipped to [lo, hi]; q = 0: not
 * quantised) into out, with each row's lowest and highest reading as lists of floats (its
 * _row_spans: the same numbers; a zero's sign may differ, which no comparison sees). None
 * where a value is not finite or a bound is zero (out is then not to be used). */
static PyObject *readings(PyObject *self, PyObject *args)
{
    PyObject *o[3];
    double q, inv_q, lo, hi;
    if (!PyArg_ParseTuple(args, "OOddddO", &o[0], &o[1], &q, &inv_q, &lo, &hi, &o[2]))
        return NULL;
    Buf b[3];
    memset(b, 0, sizeof b);
    PyObject *result = NULL, *lows = NULL, *highs = NULL;
    if (take2(o[0], &b[0], -1, -1, "true") < 0)
        goto done;
    Py_ssize_t rows = b[0].view.shape[0], n = b[0].view.shape[1];
    if (take2(o[1], &b[1], rows, n, "noise") < 0 || take(o[2], &b[2], rows * n, 1, 0, "out") < 0)
        goto done;
    Py_ssize_t t0 = b[0].view.strides[0] / 8, t1 = b[0].view.strides[1] / 8;
    Py_ssize_t n0 = b[1].view.strides[0] / 8, n1 = b[1].view.strides[1] / 8;
    const double *tp = data(&b[0]), *np_ = data(&b[1]);
    double *out = data(&b[2]);
    /* a bound at zero: numpy's clip may keep either zero of a -0.0 reading; left to it */
    if (!isfinite(q) || !isfinite(inv_q) || isnan(lo) || isnan(hi) || lo == 0.0 || hi == 0.0 ||
        n == 0)
        goto none;
    lows = PyList_New(rows);
    highs = PyList_New(rows);
    if (lows == NULL || highs == NULL)
        goto done;
    for (Py_ssize_t r = 0; r < rows; r++) {
        double least = 0.0, most = 0.0;
        for (Py_ssize_t j = 0; j < n; j++) {
            double x = tp[r * t0 + j * t1] + np_[r * n0 + j * n1];
            if (q != 0.0) {
                x = x * inv_q;
                x = nearbyint(x);
                x *= q;
            }
            if (!isfinite(x))
                goto none;
            x = x >= lo ? x : lo;
            x = x <= hi ? x : hi;
            out[r * n + j] = x;
            if (j == 0 || x < least)
                least = x;
            if (j == 0 || x > most)
                most = x;
        }
        PyObject *a = PyFloat_FromDouble(least), *z = PyFloat_FromDouble(most);
        if (a == NULL || z == NULL) {
            Py_XDECREF(a);
            Py_XDECREF(z);
            goto done;
        }
        PyList_SET_ITEM(lows, r, a);
        PyList_SET_ITEM(highs, r, z);
    }
    result = PyTuple_Pack(2, lows, highs);
    goto done;
none:
    result = Py_NewRef(Py_None);
done:
    Py_XDECREF(lows);
    Py_XDECREF(highs);
    release(b, 3);
    return result;
}

/* reading(true, noise, i, q, inv_q, lo, hi, out) -> bool: one reading of every channel, as
 * SensorBank.sample's (true + noise row i, times 1/q, rounded half to even, times q, clipped
 * to [lo, hi]; q = 0: not quantised) into out. False (out not to be used) where an array is
 * not a float64 one of the expected size (C-contiguous; noise: rows of the channels), i is
 * not a row of it, a value is not finite or a bound is zero: the reference's then. */
static PyObject *reading(PyObject *self, PyObject *args)
{
    PyObject *o[3];
    Py_ssize_t i;
    double q, inv_q, lo, hi;
    if (!PyArg_ParseTuple(args, "OOnddddO", &o[0], &o[1], &i, &q, &inv_q, &lo, &hi, &o[2]))
        return NULL;
    Buf b[3];
    memset(b, 0, sizeof b);
    int ok = take(o[0], &b[0], -1, 0, 0, "true") == 0;
    Py_ssize_t n = ok ? b[0].view.len / 8 : 0;
    ok = ok && n > 0 && take(o[1], &b[1], -1, 0, 0, "noise") == 0 &&
         take(o[2], &b[2], n, 1, 0, "out") == 0 && b[1].view.len % (n * 8) == 0 && i >= 0 &&
         i < b[1].view.len / (n * 8);
    if (!ok)
        PyErr_Clear();
    ok = ok && isfinite(q) && isfinite(inv_q) && !isnan(lo) && !isnan(hi) && lo != 0.0 &&
         hi != 0.0;
    if (ok) {
        const double *tp = data(&b[0]), *np_ = data(&b[1]) + i * n;
        double *out = data(&b[2]);
        for (Py_ssize_t j = 0; ok && j < n; j++) {
            double x = tp[j] + np_[j];
            if (q != 0.0) {
                x = x * inv_q;
                x = nearbyint(x);
                x *= q;
            }
            ok = isfinite(x);
            x = x >= lo ? x : lo;
            out[j] = x <= hi ? x : hi;
        }
    }
    release(b, 3);
    return PyBool_FromLong(ok);
}

/* Where load f lies on the load grid (TabulatedCharacteristic._locate, not extrapolating):
 * the column j and the fraction u towards column j + 1 (numpy.maximum/minimum's values). */
static void locate(const double *grid, Py_ssize_t n, double f, Py_ssize_t *j, double *u)
{
    if (n == 1) {
        *j = 0;
        *u = 0.0;
        return;
    }
    double x = f >= grid[0] ? f : grid[0];
    x = x <= grid[n - 1] ? x : grid[n - 1];
    Py_ssize_t i = count_le(grid, n, x) - 1;
    i = i > n - 2 ? n - 2 : i;
    i = i < 0 ? 0 : i;
    *j = i;
    *u = (x - grid[i]) / (grid[i + 1] - grid[i]);
}

/* columns(f, loads, table, grid, area, cols_out, slopes_out, drop_out) -> 0, 1 or 2:
 * TabulatedCharacteristic._load_columns: the table's columns at each module's load and their
 * slopes along the pressure; 2: a load beyond the table (its excess over the area written to
 * drop_out, the load taken as the table's largest), 1: none, 0: a load not finite. */
static PyObject *columns(PyObject *self, PyObject *args)
{
    PyObject *o[7];
    double area;
    if (!PyArg_ParseTuple(args, "OOOOdOOO", &o[0], &o[1], &o[2], &o[3], &area, &o[4], &o[5],
                          &o[6]))
        return NULL;
    Buf b[7];
    memset(b, 0, sizeof b);
    PyObject *result = NULL;
    if (take(o[0], &b[0], -1, 0, 0, "f") < 0 || take(o[1], &b[1], -1, 0, 0, "loads") < 0 ||
        take(o[3], &b[3], -1, 0, 0, "grid") < 0)
        goto done;
    Py_ssize_t m = b[0].view.len / 8, nl = b[1].view.len / 8, np_ = b[3].view.len / 8;
    if (nl < 1 || np_ < 2) {
        PyErr_SetString(PyExc_ValueError, "the table needs a load and two pressures");
        goto done;
    }
    if (take2(o[2], &b[2], np_, nl, "table") < 0 || take(o[4], &b[4], np_ * m, 1, 0, "cols") < 0 ||
        take(o[5], &b[5], (np_ - 1) * m, 1, 0, "slopes") < 0 ||
        take(o[6], &b[6], m, 1, 0, "drop") < 0)
        goto done;
    const double *f = data(&b[0]), *loads = data(&b[1]), *tab = data(&b[2]), *g = data(&b[3]);
    double *cols = data(&b[4]), *slopes = data(&b[5]), *drop = data(&b[6]);
    Py_ssize_t t0 = b[2].view.strides[0] / 8, t1 = b[2].view.strides[1] / 8;
    double fmax = loads[nl - 1];
    int beyond = 0;
    for (Py_ssize_t k = 0; k < m; k++) {
        if (!isfinite(f[k])) {
            result = PyLong_FromLong(0);
            goto done;
        }
        beyond |= f[k] > fmax;
    }
    for (Py_ssize_t k = 0; k < m; k++) {
        double fk = f[k], d = fk - fmax;
        if (beyond) {
            drop[k] = (d >= 0.0 ? d : 0.0) / area;
            fk = fk <= fmax ? fk : fmax;
        }
        Py_ssize_t j;
        double u;
        locate(loads, nl, fk, &j, &u);
        Py_ssize_t j1 = j + 1 < nl - 1 ? j + 1 : nl - 1;
        for (Py_ssize_t p = 0; p < np_; p++)
            cols[p * m + k] = tab[p * t0 + j * t1] * (1 - u) + tab[p * t0 + j1 * t1] * u;
        for (Py_ssize_t p = 0; p + 1 < np_; p++)
            slopes[p * m + k] = (cols[(p + 1) * m + k] - cols[p * m + k]) / (g[p + 1] - g[p]);
    }
    result = PyLong_FromLong(beyond ? 2 : 1);
done:
    release(b, 7);
    return result;
}

/* ---- Frames: a frame along the current stretch, in one call (issue 50, item 4) ----------
 *
 * SimBox.read's usual frame while a valve is open: a step along the current stretch of the
 * gas physics (ChamberBank.hold), the next reading of the ramp the sensors computed for it
 * (SensorBank.next_on_ramp), the frame, and the guard's usual decision on it
 * (SafetyGuard.check_span and _update: every reading within the sensor's range, no tripped
 * channel below its release level, the highest reading of an untripped channel plus the
 * window's rise below the trip level). Every piece of state stays in the
 * Python objects (their instance dicts, read and written here as their methods do), so every
 * other path sees what it would have seen. Frames.next decides before it changes anything:
 * None (nothing changed) wherever one of the four would not take its usual path; the caller
 * then runs the Python path, which decides the same (tests/box/test_fastsim.py). */

typedef struct {
    PyObject_HEAD
    PyObject *ch, *se, *gu;          /* the instance dicts of the chambers, sensors and guard */
    PyObject *guard;                 /* the guard itself (the caller checks it is the box's) */
    PyObject *frame_type, *set_t, *set_p, *set_s; /* PressureFrame and its slots */
    Py_ssize_t window;               /* the guard's deques' maxlen */
} Frames;

static PyObject *k_path, *k_pos, *k_valve_key, *k_supply, *k_stretch_dt, *k_solved,
    *k_solve_count, *k_i, *k_ramp_next, *k_ramp_key, *k_ramp_end, *k_ramp, *k_ramp_start,
    *k_ramp_lo, *k_ramp_hi, *k_supply_noise, *k_same, *k_span, *k_times, *k_lows, *k_history,
    *k_any_tripped, *k_min_pa, *k_max_pa, *k_trip_pa, *k_append, *k_held, *k_release_pa, *k_tripped;

static int intern_keys(void)
{
#define K(var, text)                                   \
    if ((var = PyUnicode_InternFromString(text)) == NULL) \
        return -1;
    K(k_path, "_path") K(k_pos, "_pos") K(k_valve_key, "_valve_key") K(k_supply, "_supply")
    K(k_stretch_dt, "_stretch_dt") K(k_solved, "solved") K(k_solve_count, "solve_count")
    K(k_i, "_i") K(k_ramp_next, "_ramp_next") K(k_ramp_key, "_ramp_key")
    K(k_ramp_end, "_ramp_end") K(k_ramp, "_ramp") K(k_ramp_start, "_ramp_start")
    K(k_ramp_lo, "_ramp_lo") K(k_ramp_hi, "_ramp_hi") K(k_supply_noise, "_supply_noise")
    K(k_same, "_same") K(k_span, "span") K(k_times, "_times") K(k_lows, "_lows")
    K(k_history, "_history") K(k_any_tripped, "_any_tripped") K(k_min_pa, "_min_pa")
    K(k_max_pa, "_max_pa") K(k_trip_pa, "_trip_pa") K(k_append, "append") K(k_held, "_held")
    K(k_release_pa, "_release_pa") K(k_tripped, "tripped")
#undef K
    return 0;
}

static void frames_dealloc(Frames *f)
{
    Py_XDECREF(f->ch);
    Py_XDECREF(f->se);
    Py_XDECREF(f->gu);
    Py_XDECREF(f->guard);
    Py_XDECREF(f->frame_type);
    Py_XDECREF(f->set_t);
    Py_XDECREF(f->set_p);
    Py_XDECREF(f->set_s);
    Py_TYPE(f)->tp_free((PyObject *)f);
}

static PyObject *instance_dict(PyObject *obj)
{
    PyObject *d = PyObject_GenericGetDict(obj, NULL);
    if (d != NULL && !PyDict_CheckExact(d)) {
        Py_DECREF(d);
        PyErr_SetString(PyExc_TypeError, "Frames: an object without a plain instance dict");
        return NULL;
    }
    return d;
}

/* Frames(chambers, sensors, guard, frame_type, t_slot, pressures_slot, supply_slot) */
static PyObject *frames_new(PyTypeObject *type, PyObject *args, PyObject *kw)
{
    PyObject *ch, *se, *gu, *ft, *st, *sp, *ss;
    if (!PyArg_ParseTuple(args, "OOOOOOO", &ch, &se, &gu, &ft, &st, &sp, &ss))
        return NULL;
    if (!PyType_Check(ft) || Py_TYPE(st)->tp_descr_set == NULL ||
        Py_TYPE(sp)->tp_descr_set == NULL || Py_TYPE(ss)->tp_descr_set == NULL) {
        PyErr_SetString(PyExc_TypeError, "Frames: a frame type and three settable slots");
        return NULL;
    }
    Frames *f = (Frames *)type->tp_alloc(type, 0);
    if (f == NULL)
        return NULL;
    f->ch = instance_dict(ch);
    f->se = f->ch ? instance_dict(se) : NULL;
    f->gu = f->se ? instance_dict(gu) : NULL;
    if (f->gu == NULL) {
        Py_DECREF(f);
        return NULL;
    }
    f->guard = Py_NewRef(gu);
    f->frame_type = Py_NewRef(ft);
    f->set_t = Py_NewRef(st);
    f->set_p = Py_NewRef(sp);
    f->set_s = Py_NewRef(ss);
    PyObject *times = PyDict_GetItemWithError(f->gu, k_times);
    PyObject *maxlen = times ? PyObject_GetAttrString(times, "maxlen") : NULL;
    f->window = maxlen && maxlen != Py_None ? PyLong_AsSsize_t(maxlen) : -1;
    Py_XDECREF(maxlen);
    if (f->window < 2) {
        if (!PyErr_Occurred())
            PyErr_SetString(PyExc_ValueError, "Frames: the guard's window must hold >= 2");
        Py_DECREF(f);
        return NULL;
    }
    return (PyObject *)f;
}

/* A Python int attribute as a C integer; 0 (with *ok cleared) where it is none. */
static Py_ssize_t int_of(PyObject *d, PyObject *key, int *ok)
{
    PyObject *v = PyDict_GetItemWithError(d, key);
    if (v == NULL || !PyLong_CheckExact(v)) {
        *ok = 0;
        return 0;
    }
    Py_ssize_t x = PyLong_AsSsize_t(v);
    if (x == -1 && PyErr_Occurred()) {
        PyErr_Clear();
        *ok = 0;
    }
    return x;
}

/* A float attribute (a Python float or int) as a double; *ok cleared where it is neither. */
static double float_of(PyObject *v, int *ok)
{
    if (v != NULL && PyFloat_Check(v))
        return PyFloat_AS_DOUBLE(v);
    if (v != NULL && PyLong_CheckExact(v)) {
        double x = PyLong_AsDouble(v);
        if (!(x == -1.0 && PyErr_Occurred()))
            return x;
        PyErr_Clear();
    }
    *ok = 0;
    return 0.0;
}

/* Whether a != b as Python says (1), they are equal (0), or the comparison failed (-1). */
static int differ(PyObject *a, PyObject *b)
{
    if (b == NULL)
        return -1;
    return PyObject_RichCompareBool(a, b, Py_NE);
}

static int set_int(PyObject *d, PyObject *key, Py_ssize_t x)
{
    PyObject *v = PyLong_FromSsize_t(x);
    int r = v ? PyDict_SetItem(d, key, v) : -1;
    Py_XDECREF(v);
    return r;
}

#define MAX_CHANNELS 256

/* The values of a row (a float64 buffer, or a list of floats) into x (at most MAX_CHANNELS):
 * their number, or -1 where the row is neither (no exception set). */
static Py_ssize_t values_of(PyObject *row, double *x)
{
    if (PyList_CheckExact(row)) {
        Py_ssize_t n = PyList_GET_SIZE(row);
        if (n > MAX_CHANNELS)
            return -1;
        for (Py_ssize_t k = 0; k < n; k++) {
            PyObject *v = PyList_GET_ITEM(row, k);
            if (!PyFloat_Check(v))
                return -1;
            x[k] = PyFloat_AS_DOUBLE(v);
        }
        return n;
    }
    Py_buffer v;
    if (PyObject_GetBuffer(row, &v, PyBUF_C_CONTIGUOUS | PyBUF_FORMAT) < 0) {
        PyErr_Clear();
        return -1;
    }
    const char *fmt = v.format;
    Py_ssize_t n = v.len / 8;
    int ok = v.itemsize == 8 && fmt != NULL && (fmt[0] == 'd' || (fmt[0] == '<' && fmt[1] == 'd'))
             && n <= MAX_CHANNELS;
    if (ok)
        memcpy(x, v.buf, n * sizeof(double));
    PyBuffer_Release(&v);
    return ok ? n : -1;
}

/* SafetyGuard._check_arrays on the frame ``row`` with the window's oldest row ``first``
 * (``count`` frames spanning ``span`` seconds once the frame is in; limits: the sensor's
 * range and the trip level): 1 where no channel trips or is released (the test changes
 * nothing), 0 otherwise or where the state is not as expected, -1 on an error. */
static int exact_passes(Frames *f, PyObject *row, PyObject *first, Py_ssize_t count, double span,
                        const double *limits)
{
    double x[MAX_CHANNELS], x0[MAX_CHANNELS];
    Py_ssize_t n = values_of(row, x);
    if (n < 0 || values_of(first, x0) != n)
        return 0;
    PyObject *tripped = PyDict_GetItemWithError(f->gu, k_tripped);
    PyObject *release = PyDict_GetItemWithError(f->gu, k_release_pa);
    int ok = 1;
    double release_pa = float_of(release, &ok);
    Py_buffer b;
    if (!ok || tripped == NULL || PyObject_GetBuffer(tripped, &b, PyBUF_C_CONTIGUOUS | PyBUF_FORMAT) < 0) {
        PyErr_Clear();
        return 0;
    }
    int r = b.itemsize == 1 && b.format != NULL && strcmp(b.format, "?") == 0 && b.len == n;
    const unsigned char *held = (const unsigned char *)b.buf;
    double per_frame = count >= 2 && span > 0 ? 1.0 / (double)(count - 1) : 0.0;
    for (Py_ssize_t k = 0; r && k < n; k++) {
        double v = x[k];
        int invalid = !isfinite(v) || v <= limits[0] || v >= limits[1];
        double rise = (v - x0[k]) * per_frame; /* the window's mean rise per frame */
        rise = isfinite(rise) && rise > 0.0 ? rise : 0.0;
        if (held[k] && v < release_pa && !invalid)
            r = 0; /* released */
        else if ((invalid || v + rise > limits[2]) && !held[k])
            r = 0; /* tripped */
    }
    PyBuffer_Release(&b);
    return r;
}

/* SafetyGuard._update's frame with a channel tripped (every reading within the sensor's
 * range, so finite): 1 with *high the highest reading of the untripped channels (-inf: none)
 * where no tripped channel reads below the release level, 0 where one does (the exact test
 * releases it) or the state is not as expected, -1 on an error. */
static int untripped_high(Frames *f, PyObject *row, double *high)
{
    PyObject *held = PyDict_GetItemWithError(f->gu, k_held);
    PyObject *release = PyDict_GetItemWithError(f->gu, k_release_pa);
    if (held == NULL || !PyList_CheckExact(held) || release == NULL)
        return PyErr_Occurred() ? -1 : 0;
    int ok = 1;
    double release_pa = float_of(release, &ok);
    Py_buffer v;
    if (!ok || PyObject_GetBuffer(row, &v, PyBUF_C_CONTIGUOUS | PyBUF_FORMAT) < 0) {
        PyErr_Clear();
        return 0;
    }
    const char *fmt = v.format;
    Py_ssize_t n = v.len / 8;
    int r = 0;
    if (v.itemsize == 8 && fmt != NULL && (fmt[0] == 'd' || (fmt[0] == '<' && fmt[1] == 'd')) &&
        PyList_GET_SIZE(held) == n) {
        const double *x = (const double *)v.buf;
        double top = -INFINITY;
        r = 1;
        for (Py_ssize_t k = 0; k < n; k++) {
            PyObject *h = PyList_GET_ITEM(held, k);
            if (h == Py_True) {
                if (x[k] < release_pa)
                    r = 0; /* released by the exact test */
            } else if (h == Py_False) {
                top = x[k] > top ? x[k] : top;
            } else {
                r = 0;
            }
        }
        *high = top;
    }
    PyBuffer_Release(&v);
    return r;
}

/* The guard's usual frame (SafetyGuard.check_span's inline path), decided before the frame
 * joins the window (its oldest low and time once it has: the deques' maxlen drops one): 1
 * when it passes the frame (nothing trips), 0 when the guard must decide in Python, -1 on an
 * error. */
static int guard_passes(Frames *f, PyObject *t, PyObject *row, double low, double high)
{
    PyObject *times = PyDict_GetItemWithError(f->gu, k_times);
    PyObject *lows = PyDict_GetItemWithError(f->gu, k_lows);
    PyObject *tripped = PyDict_GetItemWithError(f->gu, k_any_tripped);
    if (times == NULL || lows == NULL || (tripped != Py_False && tripped != Py_True))
        return 0;
    int ok = 1;
    double tt = float_of(t, &ok);
    double min_pa = float_of(PyDict_GetItemWithError(f->gu, k_min_pa), &ok);
    double max_pa = float_of(PyDict_GetItemWithError(f->gu, k_max_pa), &ok);
    double trip_pa = float_of(PyDict_GetItemWithError(f->gu, k_trip_pa), &ok);
    Py_ssize_t n = PyObject_Length(times);
    if (!ok || n < 0 || PyObject_Length(lows) != n || !(low > min_pa && high < max_pa))
        return PyErr_Occurred() ? -1 : 0;
    if (tripped == Py_True) { /* _update's test: no tripped channel released, the others' high */
        int r = untripped_high(f, row, &high);
        if (r <= 0)
            return r;
    }
    double first_low = low, first_t = tt;
    Py_ssize_t count = n + 1;
    if (n > 0) {
        PyObject *last = PySequence_GetItem(times, n - 1);
        double last_t = float_of(last, &ok);
        Py_XDECREF(last);
        if (!ok || tt == last_t) /* the same frame again: the guard's own answer */
            return PyErr_Occurred() ? -1 : 0;
        Py_ssize_t k = n == f->window ? 1 : 0; /* full: the oldest drops out */
        count = n == f->window ? n : n + 1;
        if (k < n) {
            PyObject *a = PySequence_GetItem(lows, k), *b = PySequence_GetItem(times, k);
            first_low = float_of(a, &ok);
            first_t = float_of(b, &ok);
            Py_XDECREF(a);
            Py_XDECREF(b);
            if (!ok)
                return PyErr_Occurred() ? -1 : 0;
        }
    }
    double rise = tt > first_t ? (high - first_low) / (double)(count - 1) : 0.0;
    if (!(rise <= 0.0)) /* a NaN rise (a NaN low in the window) fails the test below */
        high += rise;
    if (high <= trip_pa)
        return 1;
    /* the bound does not clear the frame: the exact per-channel test, which passes it where
     * it trips and releases nothing (SafetyGuard._check_arrays then changes nothing) */
    PyObject *history = PyDict_GetItemWithError(f->gu, k_history);
    if (history == NULL || PyObject_Length(history) != n)
        return PyErr_Occurred() ? -1 : 0;
    PyObject *first = n == 0 ? Py_NewRef(row) : PySequence_GetItem(history, n == f->window);
    if (first == NULL)
        return -1;
    double limits[4] = {min_pa, max_pa, trip_pa, 0.0};
    int r = exact_passes(f, row, first, count, tt - first_t, limits);
    Py_DECREF(first);
    return r;
}

static int append_to(PyObject *d, PyObject *key, PyObject *x)
{
    PyObject *q = PyDict_GetItemWithError(d, key);
    if (q == NULL)
        return -1;
    PyObject *r = PyObject_CallMethodOneArg(q, k_append, x);
    Py_XDECREF(r);
    return r ? 0 : -1;
}

/* next(t, valve_key, supply) -> the frame, or None where the Python path must run. */
static PyObject *frames_next(Frames *f, PyObject *const *args, Py_ssize_t nargs)
{
    if (nargs != 4) {
        PyErr_SetString(PyExc_TypeError, "next(t, dt, valve_key, supply)");
        return NULL;
    }
    PyObject *t = args[0], *dt = args[1], *valve_key = args[2], *supply = args[3];
    PyObject *ch = f->ch, *se = f->se;
    int ok = 1;
    /* ChamberBank.hold: a stretch runs with these valves, supply and step, a row left */
    PyObject *path = PyDict_GetItemWithError(ch, k_path);
    if (path == NULL || path == Py_None)
        goto none;
    Py_ssize_t rows = PyObject_Length(path), pos = int_of(ch, k_pos, &ok);
    if (rows < 0 || !ok || pos >= rows)
        goto none;
    if (differ(valve_key, PyDict_GetItemWithError(ch, k_valve_key)) != 0 ||
        differ(supply, PyDict_GetItemWithError(ch, k_supply)) != 0 ||
        differ(dt, PyDict_GetItemWithError(ch, k_stretch_dt)) != 0)
        goto none;
    /* SensorBank.next_on_ramp: the next reading of the ramp of this stretch, with its span */
    Py_ssize_t key = int_of(ch, k_solve_count, &ok), i = int_of(se, k_i, &ok);
    Py_ssize_t next = int_of(se, k_ramp_next, &ok), ramp_key = int_of(se, k_ramp_key, &ok);
    Py_ssize_t end = int_of(se, k_ramp_end, &ok), start = int_of(se, k_ramp_start, &ok);
    if (!ok || i != next || key != ramp_key || i >= end || i < start)
        goto none;
    PyObject *ramp = PyDict_GetItemWithError(se, k_ramp);
    PyObject *lo = PyDict_GetItemWithError(se, k_ramp_lo);
    PyObject *hi = PyDict_GetItemWithError(se, k_ramp_hi);
    PyObject *noise = PyDict_GetItemWithError(se, k_supply_noise);
    Py_ssize_t j = i - start;
    if (ramp == NULL || ramp == Py_None || lo == NULL || !PyList_CheckExact(lo) || hi == NULL ||
        !PyList_CheckExact(hi) || noise == NULL || !PyList_CheckExact(noise) ||
        j >= PyList_GET_SIZE(lo) || j >= PyList_GET_SIZE(hi) || i >= PyList_GET_SIZE(noise))
        goto none;
    PyObject *low = PyList_GET_ITEM(lo, j), *high = PyList_GET_ITEM(hi, j);
    double s = float_of(supply, &ok) + float_of(PyList_GET_ITEM(noise, i), &ok);
    double lv = float_of(low, &ok), hv = float_of(high, &ok);
    if (!ok)
        goto none;
    PyObject *row = PySequence_GetItem(ramp, j);
    if (row == NULL)
        return NULL;
    int passes = guard_passes(f, t, row, lv, hv);
    if (passes <= 0) {
        Py_DECREF(row);
        return passes < 0 ? NULL : Py_NewRef(Py_None);
    }
    /* every test passed: the four steps' changes, in Python's order */
    PyObject *sup = PyFloat_FromDouble(s);
    PyObject *span = PyTuple_Pack(3, row, low, high);
    PyObject *frame = NULL;
    if (sup == NULL || span == NULL || set_int(ch, k_pos, pos + 1) < 0 ||
        PyDict_SetItem(ch, k_solved, Py_False) < 0 || set_int(se, k_i, i + 1) < 0 ||
        PyDict_SetItem(se, k_ramp_next, PyDict_GetItem(se, k_i)) < 0 ||
        set_int(se, k_same, 0) < 0 || PyDict_SetItem(se, k_span, span) < 0 ||
        append_to(f->gu, k_history, row) < 0 || append_to(f->gu, k_lows, low) < 0 ||
        append_to(f->gu, k_times, t) < 0)
        goto out;
    PyTypeObject *tp = (PyTypeObject *)f->frame_type;
    frame = tp->tp_alloc(tp, 0);
    if (frame == NULL || Py_TYPE(f->set_t)->tp_descr_set(f->set_t, frame, t) < 0 ||
        Py_TYPE(f->set_p)->tp_descr_set(f->set_p, frame, row) < 0 ||
        Py_TYPE(f->set_s)->tp_descr_set(f->set_s, frame, sup) < 0)
        Py_CLEAR(frame);
out:
    Py_XDECREF(row);
    Py_XDECREF(sup);
    Py_XDECREF(span);
    return frame;
none:
    if (PyErr_Occurred())
        return NULL;
    return Py_NewRef(Py_None);
}

static PyObject *frames_guard(Frames *f, void *closure) { return Py_NewRef(f->guard); }

static PyMethodDef frames_methods[] = {
    {"next", (PyCFunction)(void (*)(void))frames_next, METH_FASTCALL,
     "next(t, dt, valve_key, supply) -> the frame along the current stretch with the guard's "
     "usual decision taken, or None (nothing changed: run the Python path)."},
    {NULL, NULL, 0, NULL},
};

static PyGetSetDef frames_getset[] = {
    {"guard", (getter)frames_guard, NULL, "The guard whose window this cursor fills.", NULL},
    {NULL, NULL, NULL, NULL, NULL},
};

static PyTypeObject FramesType = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "softpad.box._fastsim.Frames",
    .tp_basicsize = sizeof(Frames),
    .tp_dealloc = (destructor)frames_dealloc,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "Frames(chambers, sensors, guard, frame_type, t_slot, pressures_slot, "
              "supply_slot): the simulated box's frame along a stretch in one call.",
    .tp_methods = frames_methods,
    .tp_getset = frames_getset,
    .tp_new = frames_new,
};

static PyMethodDef methods[] = {
    {"solve", solve, METH_VARARGS,
     "solve(p, amount, cols, slopes, grid, drop, creep, patm, vt, p_out, dn_dp_out) -> bool: "
     "Newton's method (at most 6 steps) into p_out and dn_dp_out; False: not converged or not "
     "finite (the caller then runs the reference)."},
    {"interp", interp, METH_VARARGS,
     "interp(p, cols, slopes, grid, drop, out) -> bool: the table's value at each pressure "
     "into out; False: an input was not finite (out not written)."},
    {"relax", relax, METH_VARARGS,
     "relax(p, eq, flowing, a_in, a_out, dn_dp, supply, laminar, k, mode, lam_out, p_eq_out) "
     "-> bool: relaxation rates and equilibria of the channels (ChamberBank._relaxation)."},
    {"ramp", ramp, METH_VARARGS,
     "ramp(p0, p_eq, decay, lam, resolve_pa, path) -> rows: the stretch's pressures into path, "
     "and how many rows it keeps."},
    {"crosses", crosses, METH_VARARGS,
     "crosses(p, p_start, p_eq) -> bool: whether a solve landed past its equilibrium."},
    {"readings", readings, METH_VARARGS,
     "readings(true, noise, q, inv_q, lo, hi, out) -> (lows, highs) or None: quantised, "
     "clipped readings into out and each row's lowest and highest."},
    {"reading", reading, METH_VARARGS,
     "reading(true, noise, i, q, inv_q, lo, hi, out) -> bool: one quantised, clipped reading "
     "of every channel into out; False: not decided here (the reference's)."},
    {"columns", columns, METH_VARARGS,
     "columns(f, loads, table, grid, area, cols_out, slopes_out, drop_out) -> 0, 1, 2: the "
     "table's columns at the loads f and their slopes (TabulatedCharacteristic._load_columns); "
     "2: a load beyond the table (drop_out written), 0: a load not finite."},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT, "_fastsim",
    "The simulated box's exact pressure solve in compiled code (same bits as NumPy).", -1,
    methods,
};

PyMODINIT_FUNC PyInit__fastsim(void)
{
    if (intern_keys() < 0 || PyType_Ready(&FramesType) < 0)
        return NULL;
    PyObject *m = PyModule_Create(&module);
    if (m != NULL && PyModule_AddObjectRef(m, "Frames", (PyObject *)&FramesType) < 0)
        Py_CLEAR(m);
    return m;
}
