/* The MuJoCo world's steps between two box frames in compiled code (issue 50, item 1).
 *
 * One call runs up to n steps of softpad.sim._mujoco_world.MujocoWorld._mj_step: the module
 * springs follow the box's heights (low-passed), the hand is put where the kinematic arm has it
 * (its pose for each step worked out by the caller, which moves the arm), the jaw servos get
 * their setpoint, mj_step runs through MuJoCo's C API, the hand is put back, the contacts on
 * the module tops are read (module, normal force, point: what ContactSensing.update records, as
 * the same Python lists) and the hold's coasting watches the velocities (HoldCoast.observe).
 * The same arithmetic in the same order as the Python path: every operation is one IEEE-754
 * double operation (+, -, *, /, fabs, comparisons), which NumPy's element-wise loops compute
 * identically; built with -ffp-contract=off (no fused multiply-add).
 *
 * Objects being lowered onto the pad have their vertical velocity clamped as there.
 * Coasted steps (HoldCoast.coasts: mj_integratePos at the window's velocities) and steps held
 * still (MujocoWorld.rest_while_still) run here too. The loop stops early when the Python path
 * must take over: after a step with a contact of a sole or a finger while the first-touch
 * records are watched (the caller runs ContactSensing's record for that step), and before a
 * step in a coasting window while the arm moves (the caller asks HandClearance).
 *
 * No MuJoCo link: the caller passes mj_step's address (from the mujoco wheel's library) and the
 * mjModel / mjData addresses (their ``_address``); the arrays come as addresses of NumPy arrays
 * the caller keeps alive (softpad.sim._mujoco_fast). Headers: the mujoco wheel's include/.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include <math.h>
#include <stdint.h>
#include <string.h>

#include <mujoco/mujoco.h>

/* softpad.sim._mujoco_coast.STEADY_DV and ANCHOR_DV. */
#define STEADY_DV 1e-5
#define ANCHOR_DV 3e-5

typedef void (*step_fn)(const mjModel *, mjData *);
typedef void (*integrate_fn)(const mjModel *, mjtNum *, const mjtNum *, mjtNum);

/* The largest |a[dofs[j]] - b[j]| over j; NaN (returned as -1) when any difference is NaN. */
static double max_change(const double *qvel, const int64_t *dofs, Py_ssize_t n,
                         const double *ref)
{
    double m = 0.0;
    for (Py_ssize_t j = 0; j < n; j++) {
        double d = fabs(qvel[dofs[j]] - ref[j]);
        if (isnan(d))
            return -1.0;
        if (d > m)
            m = d;
    }
    return m;
}

typedef struct {
    const int64_t *dofs;
    Py_ssize_t ndofs;
    double *v0, *anchor, *coast_qvel;
    int64_t *state; /* has_v0, count, has_anchor, left, steps coasted, new velocities */
    int64_t verify, coast_steps, nv;
} Coast;

/* HoldCoast.observe after a real step (``ok``: coasting allowed now and the arm still). */
static void observe(Coast *c, const double *qvel, int ok)
{
    int64_t *st = c->state;
    if (!ok) {
        if (st[0] || st[2]) {
            st[0] = 0; st[1] = 0; st[2] = 0; st[3] = 0;
        }
        return;
    }
    if (!st[0]) {
        for (Py_ssize_t j = 0; j < c->ndofs; j++)
            c->v0[j] = qvel[c->dofs[j]];
        st[0] = 1;
        st[1] = 0;
        return;
    }
    st[1] += 1;
    if (st[1] < c->verify)
        return;
    double dv = max_change(qvel, c->dofs, c->ndofs, c->v0);
    int steady = dv >= 0.0 && dv <= STEADY_DV;
    int anchored = 1;
    if (steady && st[2]) {
        double da = max_change(qvel, c->dofs, c->ndofs, c->anchor);
        anchored = da >= 0.0 && da <= ANCHOR_DV;
    }
    if (steady && anchored) {
        if (!st[2]) {
            for (Py_ssize_t j = 0; j < c->ndofs; j++)
                c->anchor[j] = qvel[c->dofs[j]];
            st[2] = 1;
        }
        memset(c->coast_qvel, 0, (size_t)c->nv * sizeof(double));
        for (Py_ssize_t j = 0; j < c->ndofs; j++)
            c->coast_qvel[c->dofs[j]] = qvel[c->dofs[j]];
        st[3] = c->coast_steps;
        st[0] = 0;
        st[5] = 1; /* the window's velocities are new */
        return;
    }
    st[2] = 0;
    for (Py_ssize_t j = 0; j < c->ndofs; j++)
        c->v0[j] = qvel[c->dofs[j]];
    st[1] = 0;
}

/* The module contacts of the step just taken, as ContactSensing.update records them:
 * (modules, |normal force|, [x, y] points); *near: a sole's or finger's contact among them.
 * Returns a new tuple, Py_None (new reference) when no contact is on a module, NULL on error. */
static PyObject *read_contacts(const mjData *d, const int64_t *gm, const uint8_t *grip, int watch,
                               int *near)
{
    int n = d->ncon;
    PyObject *ks = NULL, *fs = NULL, *xy = NULL;
    for (int i = 0; i < n; i++) {
        const mjContact *c = d->contact + i;
        int a = c->geom1, b = c->geom2;
        int64_t k = gm[a] >= 0 ? gm[a] : gm[b];
        if (watch && (grip[a] || grip[b]))
            *near = 1;
        if (k < 0)
            continue;
        if (ks == NULL && !((ks = PyList_New(0)) && (fs = PyList_New(0)) && (xy = PyList_New(0))))
            goto fail;
        int adr = c->efc_address;
        PyObject *kk = PyLong_FromLongLong(k);
        PyObject *ff = PyFloat_FromDouble(adr >= 0 ? fabs(d->efc_force[adr]) : 0.0);
        PyObject *pt = Py_BuildValue("[dd]", c->pos[0], c->pos[1]);
        int bad = !kk || !ff || !pt || PyList_Append(ks, kk) || PyList_Append(fs, ff) ||
                  PyList_Append(xy, pt);
        Py_XDECREF(kk);
        Py_XDECREF(ff);
        Py_XDECREF(pt);
        if (bad)
            goto fail;
    }
    if (ks == NULL)
        Py_RETURN_NONE;
    return Py_BuildValue("(NNN)", ks, fs, xy);
fail:
    Py_XDECREF(ks);
    Py_XDECREF(fs);
    Py_XDECREF(xy);
    return NULL;
}

static PyObject *steps(PyObject *self, PyObject *args)
{
    unsigned long long m_adr, d_adr, fn_adr, int_adr, hands_adr, ctrl_adr, still_adr, ok_adr,
        watch_adr, hq_adr, hv_adr, spring_adr, heights_adr, gm_adr, grip_adr, dofs_adr, v0_adr,
        anchor_adr, state_adr, cq_adr, clamp_adr;
    Py_ssize_t n, nmod, ndofs, nclamp;
    double alpha, ts, lower;
    int heights_given, do_observe, time_ok, resting;
    long long verify, coast_steps;
    PyObject *pending;
    if (!PyArg_ParseTuple(args, "KKKKnKKKKKKKdKKnpKKdpppKnKKKLLKKndO!", &m_adr, &d_adr, &fn_adr,
                          &int_adr, &n, &hands_adr, &ctrl_adr, &still_adr, &ok_adr, &watch_adr,
                          &hq_adr, &hv_adr, &ts, &spring_adr, &heights_adr, &nmod,
                          &heights_given, &gm_adr, &grip_adr, &alpha, &do_observe, &time_ok,
                          &resting, &dofs_adr, &ndofs, &v0_adr, &anchor_adr, &state_adr,
                          &verify, &coast_steps, &cq_adr, &clamp_adr, &nclamp, &lower,
                          &PyList_Type, &pending))
        return NULL;
    integrate_fn mj_integratePos = (integrate_fn)(uintptr_t)int_adr;
    const uint8_t *still = (const uint8_t *)(uintptr_t)still_adr;
    const int64_t *clamp = (const int64_t *)(uintptr_t)clamp_adr;
    const mjModel *m = (const mjModel *)(uintptr_t)m_adr;
    mjData *d = (mjData *)(uintptr_t)d_adr;
    step_fn mj_step = (step_fn)(uintptr_t)fn_adr;
    const double *hands = (const double *)(uintptr_t)hands_adr;
    const double *ctrl = (const double *)(uintptr_t)ctrl_adr;
    const uint8_t *ok = (const uint8_t *)(uintptr_t)ok_adr;
    const uint8_t *watch = (const uint8_t *)(uintptr_t)watch_adr;
    const int64_t *hq = (const int64_t *)(uintptr_t)hq_adr;
    const int64_t *hv = (const int64_t *)(uintptr_t)hv_adr;
    double *spring = (double *)(uintptr_t)spring_adr;
    const double *heights = (const double *)(uintptr_t)heights_adr;
    const int64_t *gm = (const int64_t *)(uintptr_t)gm_adr;
    const uint8_t *grip = (const uint8_t *)(uintptr_t)grip_adr;
    Coast coast = {(const int64_t *)(uintptr_t)dofs_adr, ndofs, (double *)(uintptr_t)v0_adr,
                   (double *)(uintptr_t)anchor_adr, (double *)(uintptr_t)cq_adr,
                   (int64_t *)(uintptr_t)state_adr, verify, coast_steps, m->nv};
    double *qpos = d->qpos, *qvel = d->qvel;
    int last = -1; /* the last real step had module contacts (1) or not (0); -1: no real step */
    Py_ssize_t done = 0, real = 0, rested = 0;
    int stop = 0;
    int64_t *st = coast.state;
    while (done < n && !stop) {
        const double *hand = hands + 4 * done;
        int mode = 0; /* 0: a real step, 1: coasted (HoldCoast.coasts), 2: held still */
        if (st[3] > 0) { /* a coasting window: the world coasts while the arm stands */
            if (!still[done])
                break; /* Python asks whether the hand is clear (HandClearance) */
            if (time_ok) {
                st[3] -= 1;
                st[4] += 1;
                mode = 1;
            } else {
                st[0] = 0; st[1] = 0; st[2] = 0; st[3] = 0;
            }
        }
        if (mode == 0 && resting && still[done])
            mode = 2;
        if (heights_given) { /* _follow_heights: buf = h - spring; buf *= alpha; spring += buf */
            for (Py_ssize_t k = 0; k < nmod; k++) {
                double buf = heights[k] - spring[k];
                buf *= alpha;
                spring[k] += buf;
            }
        }
        if (mode) { /* _coast_step / _rest_step */
            if (mode == 1) {
                mj_integratePos(m, qpos, coast.coast_qvel, ts);
                for (int j = 0; j < 4; j++)
                    qpos[hq[j]] = hand[j];
            } else {
                rested++;
            }
            d->time += ts;
            done++;
            continue;
        }
        for (int j = 0; j < 4; j++) {
            qvel[hv[j]] = (hand[j] - qpos[hq[j]]) / ts;
            qpos[hq[j]] = hand[j];
        }
        for (int j = 0; j < m->nu; j++)
            d->ctrl[j] = ctrl[done];
        mj_step(m, d);
        for (int j = 0; j < 4; j++)
            qpos[hq[j]] = hand[j];
        for (Py_ssize_t j = 0; j < nclamp; j++) /* objects being lowered: max(v_z, -lower) */
            if (-lower > qvel[clamp[j]])
                qvel[clamp[j]] = -lower;
        int near = 0;
        PyObject *rec = d->ncon ? read_contacts(d, gm, grip, watch[done], &near) : Py_None;
        if (rec == NULL)
            return NULL;
        if (rec != Py_None) {
            int bad = PyList_Append(pending, rec);
            Py_DECREF(rec);
            if (bad)
                return NULL;
            last = 1;
        } else {
            if (d->ncon)
                Py_DECREF(rec);
            last = 0;
        }
        real++;
        if (near)
            stop = 1;
        if (do_observe)
            observe(&coast, qvel, ok[done]);
        done++;
    }
    /* (steps done, real steps among them, why it stopped: 0 all done or the arm moves in a
     * coasting window, 1 a contact to record; whether the last real step had module contacts;
     * steps held still among them) */
    return Py_BuildValue("(nniin)", done, real, stop, last, rested);
}

/* The index of the cell of a sorted axis that holds x, as numpy's
 * clip(searchsorted(axis, x, side="right") - 1, 0, n - 2). */
static Py_ssize_t cell_of(const double *axis, Py_ssize_t n, double x)
{
    Py_ssize_t lo = 0, hi = n; /* the first element > x */
    while (lo < hi) {
        Py_ssize_t mid = lo + (hi - lo) / 2;
        if (axis[mid] <= x)
            lo = mid + 1;
        else
            hi = mid;
    }
    Py_ssize_t i = lo - 1;
    if (i < 0)
        i = 0;
    if (i > n - 2)
        i = n - 2;
    return i;
}

/* NumPy's maximum and minimum of two doubles (NaN propagates; of equal values the first). */
static double np_max(double a, double b) { return (a >= b || isnan(a)) ? a : b; }
static double np_min(double a, double b) { return (a <= b || isnan(a)) ? a : b; }

static double clamp01(double t) { return np_min(np_max(0.0, t), 1.0); }

/* One pad-frame coordinate in the cast model's frame (PadResponse._to_cast_frame, seam
 * branch): k = [pitch, model_pitch, h, hm, hm / h, c1, c2] as the Python path computes them. */
static double to_cast(double p, const double *k, int inner_full)
{
    double cell = floor(p / k[0]);
    double u = p - (cell + 0.5) * k[0];
    double a = fabs(u);
    double inner = inner_full ? k[3] : a * k[4];
    double outer = k[3] + (a - k[2]) * k[5] / k[6];
    double sign = u > 0.0 ? 1.0 : (u < 0.0 ? -1.0 : (isnan(u) ? u : 0.0));
    return (cell + 0.5) * k[1] + sign * (a <= k[2] ? inner : outer);
}

/* The cast pad's response at one pressure (PadResponse._cast_factors_compiled's tuple). */
typedef struct {
    const double *table, *ax, *ay, *centres, *ref;
    Py_ssize_t nx, ny, nk;
    int seam, inner_full;
    double scale, k[7], half_side, gain1, band;
} CastPad;

#define MAX_CHAMBERS 64

static int parse_pad(PyObject *params, CastPad *c)
{
    unsigned long long table, ax, ay, centres, ref;
    double pitch, model_pitch, h, hm, hm_h, c1, c2;
    if (!PyArg_ParseTuple(params, "KnnnKKpdddddddpddddKK", &table, &c->nx, &c->ny, &c->nk, &ax,
                          &ay, &c->seam, &c->scale, &pitch, &model_pitch, &h, &hm, &hm_h, &c1,
                          &c->inner_full, &c2, &c->half_side, &c->gain1, &c->band, &centres,
                          &ref))
        return -1;
    if (c->nk < 1 || c->nk > MAX_CHAMBERS || c->nx < 2 || c->ny < 2) {
        PyErr_SetString(PyExc_ValueError, "cast table: 1-64 chambers and 2+ nodes a side");
        return -1;
    }
    c->table = (const double *)(uintptr_t)table;
    c->ax = (const double *)(uintptr_t)ax;
    c->ay = (const double *)(uintptr_t)ay;
    c->centres = (const double *)(uintptr_t)centres;
    c->ref = (const double *)(uintptr_t)ref;
    double k[7] = {pitch, model_pitch, h, hm, hm_h, c1, c2};
    memcpy(c->k, k, sizeof k);
    return 0;
}

/* PadResponse.factors of the cast pad at one pad-frame point, into out[nk]. */
static void factor_row(const CastPad *c, double px, double py, double *out)
{
    const double *ax = c->ax, *ay = c->ay;
    Py_ssize_t nx = c->nx, ny = c->ny, nk = c->nk;
    double x, y;
    if (c->seam) {
        x = to_cast(px, c->k, c->inner_full);
        y = to_cast(py, c->k, c->inner_full);
    } else {
        x = px * c->scale;
        y = py * c->scale;
    }
    Py_ssize_t i = cell_of(ax, nx, x), j = cell_of(ay, ny, y);
    double tx = clamp01((x - ax[i]) / (ax[i + 1] - ax[i]));
    double ty = clamp01((y - ay[j]) / (ay[j + 1] - ay[j]));
    double sx = 1 - tx, sy = 1 - ty;
    int on = x >= ax[0] && x <= ax[nx - 1] && y >= ay[0] && y <= ay[ny - 1];
    const double *t00 = c->table + (i * ny + j) * nk, *t10 = c->table + ((i + 1) * ny + j) * nk;
    const double *t01 = t00 + nk, *t11 = t10 + nk;
    for (Py_ssize_t m = 0; m < nk; m++) {
        double v = t00[m] * sx * sy + t10[m] * tx * sy + t01[m] * sx * ty + t11[m] * tx * ty;
        double s = on ? v : 0.0;
        /* PadResponse._line_factor and influences: the gain near the chamber's border */
        double rx = fabs(px - c->centres[2 * m]), ry = fabs(py - c->centres[2 * m + 1]);
        double d = np_max(c->half_side - np_max(rx, ry), 0.0);
        double lf = 1.0 + c->gain1 * np_max(1.0 - d / c->band, 0.0);
        out[m] = (s + (lf - 1.0) * np_max(s, 0.0)) / c->ref[m];
    }
}

static PyObject *cast_factors(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *params;
    Py_ssize_t n;
    unsigned long long pts_adr, out_adr;
    CastPad c;
    if (!PyArg_ParseTuple(args, "O!nKK", &PyTuple_Type, &params, &n, &pts_adr, &out_adr) ||
        parse_pad(params, &c) < 0)
        return NULL;
    const double *pts = (const double *)(uintptr_t)pts_adr;
    double *out = (double *)(uintptr_t)out_adr;
    for (Py_ssize_t r = 0; r < n; r++)
        factor_row(&c, pts[2 * r], pts[2 * r + 1], out + r * c.nk);
    Py_RETURN_NONE;
}

/* ContactSensing._flush of the cast pad: for every step's record (modules, forces, points),
 * shares = factors * f, summed over the step's contacts in order (NumPy's sum over axis 0:
 * row after row from the first), added to total. */
static PyObject *cast_weigh(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *params, *pending;
    unsigned long long total_adr;
    CastPad c;
    if (!PyArg_ParseTuple(args, "O!O!K", &PyTuple_Type, &params, &PyList_Type, &pending,
                          &total_adr) ||
        parse_pad(params, &c) < 0)
        return NULL;
    double *total = (double *)(uintptr_t)total_adr;
    double row[MAX_CHAMBERS], acc[MAX_CHAMBERS];
    for (Py_ssize_t r = 0; r < PyList_GET_SIZE(pending); r++) {
        /* a record's parts as sequences (the steps' lists, or arrays) */
        PyObject *rec = PySequence_Fast(PyList_GET_ITEM(pending, r), "a step's record");
        if (rec == NULL)
            return NULL;
        PyObject *fs = NULL, *xy = NULL;
        int ok = PySequence_Fast_GET_SIZE(rec) == 3 &&
                 (fs = PySequence_Fast(PySequence_Fast_GET_ITEM(rec, 1), "forces")) != NULL &&
                 (xy = PySequence_Fast(PySequence_Fast_GET_ITEM(rec, 2), "points")) != NULL;
        Py_ssize_t n = ok ? PySequence_Fast_GET_SIZE(fs) : 0;
        if (ok && (n == 0 || PySequence_Fast_GET_SIZE(xy) != n)) {
            PyErr_SetString(PyExc_ValueError, "a step's record has no or unequal contacts");
            ok = 0;
        } else if (!ok && !PyErr_Occurred()) {
            PyErr_SetString(PyExc_TypeError, "a step's record must be (modules, forces, points)");
        }
        for (Py_ssize_t i = 0; ok && i < n; i++) {
            PyObject *pt = PySequence_Fast_GET_ITEM(xy, i);
            double f = PyFloat_AsDouble(PySequence_Fast_GET_ITEM(fs, i));
            PyObject *px = PySequence_GetItem(pt, 0), *py = PySequence_GetItem(pt, 1);
            double x = px ? PyFloat_AsDouble(px) : -1.0, y = py ? PyFloat_AsDouble(py) : -1.0;
            Py_XDECREF(px);
            Py_XDECREF(py);
            if (PyErr_Occurred()) {
                ok = 0;
                break;
            }
            factor_row(&c, x, y, row);
            for (Py_ssize_t m = 0; m < c.nk; m++) {
                double share = row[m] * f;
                acc[m] = i ? acc[m] + share : share;
            }
        }
        Py_XDECREF(fs);
        Py_XDECREF(xy);
        Py_DECREF(rec);
        if (!ok)
            return NULL;
        for (Py_ssize_t m = 0; m < c.nk; m++)
            total[m] += acc[m];
    }
    Py_RETURN_NONE;
}

static PyMethodDef methods[] = {
    {"cast_factors", cast_factors, METH_VARARGS,
     "cast_factors(pad, n, points, out): PadResponse.factors of the cast pad at n points into "
     "out (n, k); pad: (table, nx, ny, k, x_axis, y_axis, seam, scale, pitch, model_pitch, h, "
     "hm, hm_h, c1, inner_full, c2, half_side, gain_1, band, centres, ref), addresses of the "
     "caller's arrays (softpad.sim._response)."},
    {"cast_weigh", cast_weigh, METH_VARARGS,
     "cast_weigh(pad, pending, total): ContactSensing._flush of the cast pad: each step's "
     "equivalent loads (shares summed in contact order) added to total (k)."},
    {"steps", steps, METH_VARARGS,
     "steps(model, data, mj_step, mj_integratePos, n, hands, ctrl, still, ok, watch, hand_q, "
     "hand_v, ts, spring, heights, n_modules, heights_given, geom_module, grip, alpha, observe, "
     "time_ok, resting, dofs, n_dofs, v0, anchor, state, verify_steps, coast_steps, coast_qvel, "
     "clamp, n_clamp, lower, pending) -> (done, real, stop, last, rested): up "
     "to n MuJoCo steps of the world (addresses of the caller's arrays; "
     "softpad.sim._mujoco_fast)."},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT, "_fastworld",
    "The MuJoCo world's steps between two box frames in compiled code (same bits as Python).",
    -1, methods,
};

PyMODINIT_FUNC PyInit__fastworld(void) { return PyModule_Create(&module); }
