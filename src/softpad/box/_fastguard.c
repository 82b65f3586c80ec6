/* The box's over-pressure guard in compiled code, on its own thread, without the interpreter
 * lock (issue 49 item 4): no stall of the Python side (a collection, a flood of queries, a C
 * call holding the GIL) can hold it up.
 *
 * Every period (absolute deadlines on CLOCK_MONOTONIC) it reads each channel's IIO file
 * (in_voltageK_raw, pread from offset 0), calibrates it (offset + factor * raw, pascals) and,
 * on a channel above the trip level, closes its inflation valve and opens its deflation valve,
 * again every tick until the reading is below the release level (then it leaves the valves to
 * the daemon: a vented channel keeps venting until commanded). A reading that cannot be parsed
 * closes the inflation valve.
 *
 * Valve lines are written through one of two back-ends, per line:
 *   kind 0: a shared file, one byte per line at its index (the test's fake GPIO);
 *   kind 1: a libgpiod v2 line request's file descriptor, the line at its index in the request
 *           (GPIO_V2_LINE_SET_VALUES_IOCTL, the ioctl libgpiod itself issues).
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include <errno.h>
#include <fcntl.h>
#include <linux/gpio.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <time.h>
#include <unistd.h>

#define MAX_CHANNELS 64

typedef struct {
    int kind;  /* 0: shared file, 1: gpiod request */
    int fd;
    int index;
    int level; /* the level that closes (inflation) or opens (deflation) the valve */
} Line;

typedef struct {
    PyObject_HEAD
    int n;
    int iio_fd[MAX_CHANNELS];
    double offset[MAX_CHANNELS];
    double factor[MAX_CHANNELS];
    Line inflate[MAX_CHANNELS]; /* level: closed */
    Line deflate[MAX_CHANNELS]; /* level: open */
    double trip_pa, release_pa;
    long period_ns;
    pthread_t thread;
    int running;
    atomic_int stop;
    atomic_long ticks, trips, missed, bad_reads;
    atomic_int latched[MAX_CHANNELS];
} Guard;

static int write_line(const Line *l)
{
    if (l->kind == 0) {
        unsigned char b = (unsigned char)l->level;
        return pwrite(l->fd, &b, 1, l->index) == 1 ? 0 : -1;
    }
    struct gpio_v2_line_values v;
    v.mask = 1ULL << l->index;
    v.bits = l->level ? v.mask : 0;
    return ioctl(l->fd, GPIO_V2_LINE_SET_VALUES_IOCTL, &v);
}

static int read_raw(int fd, double *out)
{
    char buf[64];
    ssize_t k = pread(fd, buf, sizeof buf - 1, 0);
    if (k <= 0)
        return -1;
    buf[k] = 0;
    char *end;
    errno = 0;
    double v = strtod(buf, &end);
    if (end == buf || errno != 0 || !isfinite(v))
        return -1;
    *out = v;
    return 0;
}

static void tick(Guard *g)
{
    for (int k = 0; k < g->n; k++) {
        double raw;
        if (read_raw(g->iio_fd[k], &raw) != 0) {
            atomic_fetch_add(&g->bad_reads, 1);
            write_line(&g->inflate[k]); /* no valid reading: no inflation */
            continue;
        }
        double p = g->offset[k] + g->factor[k] * raw;
        if (p > g->trip_pa) {
            if (!atomic_exchange(&g->latched[k], 1))
                atomic_fetch_add(&g->trips, 1);
        } else if (p < g->release_pa) {
            atomic_store(&g->latched[k], 0);
        }
        if (atomic_load(&g->latched[k])) {
            write_line(&g->inflate[k]); /* close first, then open: never both open */
            write_line(&g->deflate[k]);
        }
    }
}

static void *run(void *arg)
{
    Guard *g = (Guard *)arg;
    struct timespec due;
    clock_gettime(CLOCK_MONOTONIC, &due);
    while (!atomic_load(&g->stop)) {
        tick(g);
        atomic_fetch_add(&g->ticks, 1);
        due.tv_nsec += g->period_ns;
        while (due.tv_nsec >= 1000000000L) {
            due.tv_nsec -= 1000000000L;
            due.tv_sec += 1;
        }
        struct timespec now;
        clock_gettime(CLOCK_MONOTONIC, &now);
        long late_ns = (now.tv_sec - due.tv_sec) * 1000000000L + (now.tv_nsec - due.tv_nsec);
        if (late_ns >= g->period_ns) { /* whole periods late: skip them, count them */
            long skip = late_ns / g->period_ns;
            atomic_fetch_add(&g->missed, skip);
            due.tv_nsec += skip * g->period_ns;
            due.tv_sec += due.tv_nsec / 1000000000L;
            due.tv_nsec %= 1000000000L;
        }
        clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &due, NULL);
    }
    return NULL;
}

static int parse_line(PyObject *item, Line *out)
{
    return PyArg_ParseTuple(item, "iiii", &out->kind, &out->fd, &out->index, &out->level) ? 0 : -1;
}

static int Guard_init(Guard *g, PyObject *args, PyObject *kwds)
{
    static char *names[] = {"iio_paths", "offsets", "factors", "inflate", "deflate",
                            "trip_pa", "release_pa", "rate_hz", NULL};
    PyObject *paths, *offs, *facs, *infl, *defl;
    double rate;
    if (!PyArg_ParseTupleAndKeywords(args, kwds, "OOOOOddd", names, &paths, &offs, &facs, &infl,
                                     &defl, &g->trip_pa, &g->release_pa, &rate))
        return -1;
    Py_ssize_t n = PySequence_Size(paths);
    if (n < 1 || n > MAX_CHANNELS || PySequence_Size(offs) != n || PySequence_Size(facs) != n ||
        PySequence_Size(infl) != n || PySequence_Size(defl) != n) {
        PyErr_SetString(PyExc_ValueError, "1..64 channels, the same number in every list");
        return -1;
    }
    if (!(rate >= 1.0 && rate <= 100000.0) || !(g->release_pa < g->trip_pa)) {
        PyErr_SetString(PyExc_ValueError, "rate_hz within 1..1e5 and release_pa < trip_pa");
        return -1;
    }
    g->n = (int)n;
    g->period_ns = (long)(1e9 / rate);
    for (int k = 0; k < g->n; k++)
        g->iio_fd[k] = -1;
    for (int k = 0; k < g->n; k++) {
        PyObject *p = PySequence_GetItem(paths, k), *o = PySequence_GetItem(offs, k);
        PyObject *f = PySequence_GetItem(facs, k), *i = PySequence_GetItem(infl, k);
        PyObject *d = PySequence_GetItem(defl, k);
        int bad = !p || !o || !f || !i || !d;
        const char *path = bad ? NULL : PyUnicode_AsUTF8(p);
        if (!bad && path) {
            g->offset[k] = PyFloat_AsDouble(o);
            g->factor[k] = PyFloat_AsDouble(f);
            bad = PyErr_Occurred() || parse_line(i, &g->inflate[k]) || parse_line(d, &g->deflate[k]);
            if (!bad) {
                g->iio_fd[k] = open(path, O_RDONLY | O_CLOEXEC);
                if (g->iio_fd[k] < 0) {
                    PyErr_SetFromErrnoWithFilename(PyExc_OSError, path);
                    bad = 1;
                }
            }
        } else {
            bad = 1;
        }
        Py_XDECREF(p); Py_XDECREF(o); Py_XDECREF(f); Py_XDECREF(i); Py_XDECREF(d);
        if (bad)
            return -1;
    }
    return 0;
}

static PyObject *Guard_start(Guard *g, PyObject *Py_UNUSED(unused))
{
    if (!g->running) {
        atomic_store(&g->stop, 0);
        int err = pthread_create(&g->thread, NULL, run, g);
        if (err) {
            errno = err;
            return PyErr_SetFromErrno(PyExc_OSError);
        }
        g->running = 1;
    }
    Py_RETURN_NONE;
}

static PyObject *Guard_stop(Guard *g, PyObject *Py_UNUSED(unused))
{
    if (g->running) {
        atomic_store(&g->stop, 1);
        Py_BEGIN_ALLOW_THREADS
        pthread_join(g->thread, NULL);
        Py_END_ALLOW_THREADS
        g->running = 0;
    }
    Py_RETURN_NONE;
}

static PyObject *Guard_stats(Guard *g, PyObject *Py_UNUSED(unused))
{
    PyObject *latched = PyList_New(g->n);
    if (!latched)
        return NULL;
    for (int k = 0; k < g->n; k++)
        PyList_SET_ITEM(latched, k, PyBool_FromLong(atomic_load(&g->latched[k])));
    return Py_BuildValue("{s:l,s:l,s:l,s:l,s:N,s:O}", "ticks", atomic_load(&g->ticks), "trips",
                         atomic_load(&g->trips), "missed_ticks", atomic_load(&g->missed),
                         "bad_reads", atomic_load(&g->bad_reads), "venting", latched, "running",
                         g->running ? Py_True : Py_False);
}

static void Guard_dealloc(Guard *g)
{
    if (g->running) {
        atomic_store(&g->stop, 1);
        pthread_join(g->thread, NULL);
    }
    for (int k = 0; k < g->n; k++)
        if (g->iio_fd[k] >= 0)
            close(g->iio_fd[k]);
    Py_TYPE(g)->tp_free((PyObject *)g);
}

static PyMethodDef Guard_methods[] = {
    {"start", (PyCFunction)Guard_start, METH_NOARGS, "Start the guard's thread (idempotent)."},
    {"stop", (PyCFunction)Guard_stop, METH_NOARGS, "Stop and join the thread (idempotent)."},
    {"stats", (PyCFunction)Guard_stats, METH_NOARGS,
     "Ticks, trips, missed ticks, bad reads and the channels being vented."},
    {NULL, NULL, 0, NULL},
};

static PyTypeObject GuardType = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "softpad.box._fastguard.Guard",
    .tp_doc = "Guard(iio_paths, offsets, factors, inflate, deflate, trip_pa, release_pa, "
              "rate_hz): the over-pressure guard on its own thread, without the GIL.",
    .tp_basicsize = sizeof(Guard),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_new = PyType_GenericNew,
    .tp_init = (initproc)Guard_init,
    .tp_dealloc = (destructor)Guard_dealloc,
    .tp_methods = Guard_methods,
};

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT,
    .m_name = "_fastguard",
    .m_doc = "The box's over-pressure guard in compiled code (see softpad.box._hardware).",
    .m_size = -1,
};

PyMODINIT_FUNC PyInit__fastguard(void)
{
    if (PyType_Ready(&GuardType) < 0)
        return NULL;
    PyObject *m = PyModule_Create(&module);
    if (!m)
        return NULL;
    Py_INCREF(&GuardType);
    if (PyModule_AddObject(m, "Guard", (PyObject *)&GuardType) < 0) {
        Py_DECREF(&GuardType);
        Py_DECREF(m);
        return NULL;
    }
    return m;
}
