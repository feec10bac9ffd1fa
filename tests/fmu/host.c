/* A minimal FMI 2.0 co-simulation host without Python: loads an FMU's shared library with
 * dlopen, instantiates it, sets real values, steps with a fixed communication step and prints
 * "t y1 y2 ..." per step. Log messages go to stderr.
 *
 * usage: host LIBRARY GUID T_END H VR_OUT[,VR_OUT...] [VR=VALUE ...]
 * exit status: 0 on success, 2 on usage errors, 3 when an FMI call does not return fmi2OK.
 */
#include <dlfcn.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

int main(int argc, char **argv) {
    fmi2CallbackFunctions cb = {logger, calloc, free, NULL, NULL};
    fmi2ValueReference out[64];
    fmi2Real y[64];
    size_t n_out = 0;
    double t = 0.0, t_end, h;
    char *tok;
    int i;
    fmi2Status status;
    void *lib;
    fmi2Component c;
    if (argc < 6) return 2;
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
        LOAD(fmi2GetRealTYPE, get_real, "fmi2GetReal")
        LOAD(fmi2DoStepTYPE, do_step, "fmi2DoStep")
        LOAD(fmi2TerminateTYPE, terminate, "fmi2Terminate")
        LOAD(fmi2FreeInstanceTYPE, free_instance, "fmi2FreeInstance")
        t_end = atof(argv[3]);
        h = atof(argv[4]);
        for (tok = strtok(argv[5], ","); tok != NULL && n_out < 64; tok = strtok(NULL, ","))
            out[n_out++] = (fmi2ValueReference)strtoul(tok, NULL, 10);
        c = instantiate("host", fmi2CoSimulation, argv[2], "", &cb, fmi2False, fmi2False);
        if (c == NULL) {
            fprintf(stderr, "fmi2Instantiate failed\n");
            return 3;
        }
        CHECK(setup(c, fmi2True, 1e-8, 0.0, fmi2False, 0.0))
        CHECK(enter_init(c))
        for (i = 6; i < argc; ++i) {
            fmi2ValueReference vr = (fmi2ValueReference)strtoul(argv[i], &tok, 10);
            fmi2Real v = atof(tok + 1);
            CHECK(set_real(c, &vr, 1, &v))
        }
        CHECK(exit_init(c))
        while (t < t_end - 1e-12) {
            CHECK(do_step(c, t, h, fmi2True))
            t += h;
            CHECK(get_real(c, out, n_out, y))
            printf("%.17g", t);
            for (i = 0; i < (int)n_out; ++i) printf(" %.17g", y[i]);
            printf("\n");
        }
        CHECK(terminate(c))
        free_instance(c);
    }
    dlclose(lib);
    return 0;
}
