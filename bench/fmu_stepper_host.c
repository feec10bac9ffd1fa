/* Timing host of bench/fmu_stepper.py: loads an FMI 2.0 co-simulation FMU's shared library with
 * dlopen, instantiates it with the given tolerance, sets inputs, ramps one input linearly from 0
 * to its final value (fmi2SetRealInputDerivatives, so the ramp is exact inside each step), calls
 * fmi2DoStep N times with a fixed communication step and prints
 *   "ns_per_doStep <mean wall time of one fmi2DoStep call [ns]> <mean CPU time of the
 *   thread [ns]>"
 * then "t y1 y2 ..." per communication point. The log (with the stepper's counters at
 * fmi2Terminate) goes to stderr.
 *
 * usage: fmu_stepper_host LIBRARY GUID TOL H N RAMP_VR RAMP_VALUE RAMP_TIME VR_OUT[,...]
 *        [VR=VALUE ...]
 * exit status: 0 on success, 2 on usage errors, 3 when an FMI call does not return fmi2OK.
 */
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "fmi2Functions.h"

static void logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                   fmi2String category, fmi2String message, ...) {
    (void)env;
    fprintf(stderr, "[%s] %s (status %d): %s\n", category, name, (int)status, message);
}

#define LOAD(type, var, sym)                                                \
    type *var = (type *)dlsym(lib, sym);                                    \
    if (var == NULL) {                                                      \
        fprintf(stderr, "missing symbol %s\n", sym);                        \
        return 2;                                                           \
    }

#define CHECK(call)                                                         \
    if ((status = (call)) != fmi2OK) {                                      \
        fprintf(stderr, "%s returned %d\n", #call, (int)status);            \
        return 3;                                                           \
    }

static double now_ns(clockid_t clock) {
    struct timespec ts;
    clock_gettime(clock, &ts);
    return 1e9 * (double)ts.tv_sec + (double)ts.tv_nsec;
}

int main(int argc, char **argv) {
    fmi2CallbackFunctions cb = {logger, calloc, free, NULL, NULL};
    fmi2ValueReference out[64], ramp_vr;
    fmi2Integer order1 = 1;
    size_t n_out = 0;
    double tol, h, ramp_value, ramp_time, wall = 0.0, cpu = 0.0, *rows;
    long n, k;
    char *tok;
    int i;
    fmi2Status status;
    void *lib;
    fmi2Component c;
    if (argc < 10) return 2;
    lib = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
    if (lib == NULL) {
        fprintf(stderr, "dlopen: %s\n", dlerror());
        return 2;
    }
    {
        LOAD(fmi2InstantiateTYPE, instantiate, "fmi2Instantiate")
        LOAD(fmi2SetupExperimentTYPE, setup, "fmi2SetupExperiment")
        LOAD(fmi2EnterInitializationModeTYPE, enter_init, "fmi2EnterInitializationMode")
        LOAD(fmi2ExitInitializationModeTYPE, exit_init, "fmi2ExitInitializationMode")
        LOAD(fmi2SetRealTYPE, set_real, "fmi2SetReal")
        LOAD(fmi2SetRealInputDerivativesTYPE, set_der, "fmi2SetRealInputDerivatives")
        LOAD(fmi2GetRealTYPE, get_real, "fmi2GetReal")
        LOAD(fmi2DoStepTYPE, do_step, "fmi2DoStep")
        LOAD(fmi2TerminateTYPE, terminate, "fmi2Terminate")
        LOAD(fmi2FreeInstanceTYPE, free_instance, "fmi2FreeInstance")
        tol = atof(argv[3]);
        h = atof(argv[4]);
        n = atol(argv[5]);
        ramp_vr = (fmi2ValueReference)strtoul(argv[6], NULL, 10);
        ramp_value = atof(argv[7]);
        ramp_time = atof(argv[8]);
        for (tok = strtok(argv[9], ","); tok != NULL && n_out < 64; tok = strtok(NULL, ","))
            out[n_out++] = (fmi2ValueReference)strtoul(tok, NULL, 10);
        rows = (double *)calloc((size_t)n * (n_out + 1), sizeof(double));
        c = instantiate("host", fmi2CoSimulation, argv[2], "", &cb, fmi2False, fmi2True);
        if (c == NULL || rows == NULL) {
            fprintf(stderr, "fmi2Instantiate failed\n");
            return 3;
        }
        CHECK(setup(c, fmi2True, tol, 0.0, fmi2False, 0.0))
        CHECK(enter_init(c))
        for (i = 10; i < argc; ++i) {
            fmi2ValueReference vr = (fmi2ValueReference)strtoul(argv[i], &tok, 10);
            fmi2Real v = atof(tok + 1);
            CHECK(set_real(c, &vr, 1, &v))
        }
        {
            fmi2Real zero = 0.0;
            CHECK(set_real(c, &ramp_vr, 1, &zero))
        }
        CHECK(exit_init(c))
        for (k = 0; k < n; ++k) {
            double t = (double)k * h, t0, c0;
            /* input value at t and its slope over [t, t + h] (the ramp's knot is a multiple of
             * h) */
            fmi2Real u = t < ramp_time ? ramp_value * t / ramp_time : ramp_value;
            fmi2Real du = t + 0.5 * h < ramp_time ? ramp_value / ramp_time : 0.0;
            CHECK(set_real(c, &ramp_vr, 1, &u))
            CHECK(set_der(c, &ramp_vr, 1, &order1, &du))
            t0 = now_ns(CLOCK_MONOTONIC);
            c0 = now_ns(CLOCK_THREAD_CPUTIME_ID);
            CHECK(do_step(c, t, h, fmi2True))
            cpu += now_ns(CLOCK_THREAD_CPUTIME_ID) - c0;
            wall += now_ns(CLOCK_MONOTONIC) - t0;
            rows[k * (n_out + 1)] = (double)(k + 1) * h;
            CHECK(get_real(c, out, n_out, rows + k * (n_out + 1) + 1))
        }
        CHECK(terminate(c))
        free_instance(c);
        printf("ns_per_doStep %.1f %.1f\n", wall / (double)n, cpu / (double)n);
        for (k = 0; k < n; ++k) {
            for (i = 0; i <= (int)n_out; ++i)
                printf(i ? " %.17g" : "%.17g", rows[k * (n_out + 1) + i]);
            printf("\n");
        }
        free(rows);
    }
    dlclose(lib);
    return 0;
}
