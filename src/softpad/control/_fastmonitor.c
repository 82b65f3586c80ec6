/* The fault monitor's steady-rise rates in compiled code (issue 50: the trial's monitor).
 *
 * rates(times, sums, lo, hi, t, offsets, sealed_from, window_s, between, within) -> int:
 * softpad.control._safety._SteadyRise.update's rates, from the half-window edges on: the same
 * IEEE-754 double operations in the same order as its NumPy reference (searchsorted, the
 * half windows' means, their levels, the rates between and within the windows, NaN for a
 * channel not sealed throughout), so the same bits (tests/control/test_fast_monitor.py).
 * Built with -ffp-contract=off: no fused multiply-add. Returns 1 (between and within
 * written), 0 (no rates: no channel sealed throughout, or a half window without a sample) or
 * -1 (not decided here: the times out of order, or an edge before the kept times; the caller
 * runs the reference).
 *
 * No NumPy headers: float64 arrays through the buffer protocol (C-contiguous), results into
 * arrays the caller allocated.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include <math.h>
#include <string.h>

#define MAX_EDGES 64

static int take(PyObject *obj, Py_buffer *v, int writable, const char *what)
{
    int flags = PyBUF_C_CONTIGUOUS | PyBUF_FORMAT | (writable ? PyBUF_WRITABLE : 0);
    if (PyObject_GetBuffer(obj, v, flags) < 0)
        return -1;
    const char *f = v->format;
    if (v->itemsize != 8 || f == NULL || !(f[0] == 'd' || (f[0] == '<' && f[1] == 'd'))) {
        PyErr_Format(PyExc_TypeError, "%s must be a float64 array", what);
        PyBuffer_Release(v);
        return -1;
    }
    return 0;
}

/* Number of the m sorted values <= x (numpy.searchsorted(values, x, side="right")). */
static Py_ssize_t count_le(const double *v, Py_ssize_t m, double x)
{
    Py_ssize_t a = 0, b = m;
    while (a < b) {
        Py_ssize_t mid = a + ((b - a) >> 1);
        if (v[mid] <= x)
            a = mid + 1;
        else
            b = mid;
    }
    return a;
}

static int compute(const double *times, const double *sums, Py_ssize_t n, Py_ssize_t lo,
                   Py_ssize_t hi, double t, const double *offsets, Py_ssize_t k,
                   const double *from, double window_s, double *between, double *within)
{
    Py_ssize_t m = hi - lo, edges[MAX_EDGES];
    const double *kept = times + lo;
    for (Py_ssize_t i = 1; i < m; i++)
        if (!(kept[i - 1] <= kept[i]))
            return -1; /* not sorted (or NaN): numpy's search is the reference's */
    for (Py_ssize_t e = 0; e < k; e++) {
        edges[e] = count_le(kept, m, t - offsets[e]) - 1;
        if (edges[e] < 0)
            return -1; /* kept[-1] in the reference: Python's own indexing */
    }
    double last = kept[edges[k - 1]];
    int all_old = 1, any_old = 0;
    for (Py_ssize_t j = 0; j < n; j++) {
        int old = from[j] > last;
        all_old &= old;
        any_old |= old;
    }
    if (all_old)
        return 0;
    for (Py_ssize_t e = 0; e + 1 < k; e++)
        if ((double)(edges[e] - edges[e + 1]) < 1.0)
            return 0;
    Py_ssize_t count = (k - 3) / 2; /* k = 2 count + 3 edges */
    double half = 0.5 * window_s;
    for (Py_ssize_t j = 0; j < n; j++) {
        double halves[MAX_EDGES];
        for (Py_ssize_t e = 0; e + 1 < k; e++) {
            double c = (double)(edges[e] - edges[e + 1]);
            const double *a = sums + (lo + edges[e]) * n, *b = sums + (lo + edges[e + 1]) * n;
            halves[e] = (a[j] - b[j]) / c;
        }
        double levels[MAX_EDGES];
        for (Py_ssize_t w = 0; w <= count; w++) {
            levels[w] = 0.5 * (halves[2 * w] + halves[2 * w + 1]);
            within[w * n + j] = (halves[2 * w] - halves[2 * w + 1]) / half;
        }
        for (Py_ssize_t w = 0; w < count; w++)
            between[w * n + j] = (levels[w] - levels[w + 1]) / window_s;
        if (any_old && from[j] > last) {
            for (Py_ssize_t w = 0; w < count; w++)
                between[w * n + j] = NAN;
            for (Py_ssize_t w = 0; w <= count; w++)
                within[w * n + j] = NAN;
        }
    }
    return 1;
}

static PyObject *rates(PyObject *self, PyObject *args)
{
    PyObject *o[6];
    Py_ssize_t lo, hi;
    double t, window_s;
    if (!PyArg_ParseTuple(args, "OOnndOOdOO", &o[0], &o[1], &lo, &hi, &t, &o[2], &o[3], &window_s,
                          &o[4], &o[5]))
        return NULL;
    Py_buffer v[6];
    int held = 0;
    PyObject *result = NULL;
    const char *names[6] = {"times", "sums", "offsets", "sealed_from", "between", "within"};
    for (; held < 6; held++)
        if (take(o[held], &v[held], held >= 4, names[held]) < 0)
            goto done;
    Py_ssize_t size = v[0].len / 8, n = v[3].len / 8, k = v[2].len / 8;
    Py_ssize_t count = (k - 3) / 2;
    if (n < 1 || k < 3 || k % 2 == 0 || k > MAX_EDGES || v[1].len != size * n * 8 ||
        v[4].len != count * n * 8 || v[5].len != (count + 1) * n * 8 || lo < 0 || hi > size ||
        hi - lo < 1) {
        PyErr_SetString(PyExc_ValueError,
                        "rates: times (size), sums (size, n), 0 <= lo < hi <= size, offsets of "
                        "2 count + 3 edges (at most 63), between (count, n), within (count + 1, n)");
        goto done;
    }
    int r = compute((const double *)v[0].buf, (const double *)v[1].buf, n, lo, hi, t,
                    (const double *)v[2].buf, k, (const double *)v[3].buf, window_s,
                    (double *)v[4].buf, (double *)v[5].buf);
    result = PyLong_FromLong(r);
done:
    for (int i = 0; i < held; i++)
        PyBuffer_Release(&v[i]);
    return result;
}

static PyMethodDef methods[] = {
    {"rates", rates, METH_VARARGS,
     "rates(times, sums, lo, hi, t, offsets, sealed_from, window_s, between, within) -> 1, 0 "
     "or -1: the steady-rise rates into between and within (1), none (0), or not decided "
     "here (-1: run the reference)."},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT, "_fastmonitor",
    "The fault monitor's steady-rise rates in compiled code (same bits as NumPy).", -1, methods,
};

PyMODINIT_FUNC PyInit__fastmonitor(void) { return PyModule_Create(&module); }
