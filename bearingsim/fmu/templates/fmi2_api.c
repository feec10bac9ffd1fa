/* bearingsim FMU runtime: the FMI 2.0 API (Model Exchange and Co-Simulation) on top of
 * bsm_model.h. Generic: the model-specific part is in model_config.h and model_data.c. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#include "bsm_model.h"

typedef enum {
    MODE_INSTANTIATED = 1,
    MODE_INITIALIZATION = 2,
    MODE_EVENT = 4,
    MODE_CONTINUOUS = 8,
    MODE_STEP_COMPLETE = 16,
    MODE_TERMINATED = 32,
    MODE_ERROR = 64
} Mode;

#define ANY_MODE 0x7f
#define SETUP_MODES (MODE_INSTANTIATED | MODE_INITIALIZATION)
#define TUNE_MODES (SETUP_MODES | MODE_EVENT | MODE_STEP_COMPLETE)
#define RUN_MODES (MODE_INITIALIZATION | MODE_EVENT | MODE_CONTINUOUS | MODE_STEP_COMPLETE)

#define SERIAL_MAGIC 0x42534d32u /* "BSM2" */

typedef struct {
    BsmInstance m;
    fmi2CallbackFunctions cb;
} Fmi2Instance;

static void fmi2_logger(void *host, BsmStatus status, const char *category,
                        const char *message) {
    Fmi2Instance *c = (Fmi2Instance *)host;
    if (c->cb.logger != NULL)
        c->cb.logger(c->cb.componentEnvironment, c->m.instance_name, (fmi2Status)status,
                     category, message);
}

/* Check that `c` is an instance in one of `modes`; log and return fmi2Error otherwise. */
static fmi2Status check_mode(Fmi2Instance *c, int modes, const char *function) {
    if (c == NULL) return fmi2Error;
    if (c->m.s.mode & modes) return fmi2OK;
    bsm_log(&c->m, BSM_ERROR, "logStatusError", "%s must not be called in this state",
            function);
    return fmi2Error;
}

/* Record an error status; fmi2Error leaves the instance in the error state. */
static fmi2Status fail(Fmi2Instance *c, BsmStatus st) {
    if (st == BSM_ERROR) c->m.s.mode = MODE_ERROR;
    return (fmi2Status)st;
}

#define INSTANCE(function, modes)                                         \
    Fmi2Instance *c = (Fmi2Instance *)component;                         \
    if (check_mode(c, (modes), (function)) != fmi2OK) return fmi2Error;

/* ------------------------------------------------------------------ common functions */
const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }

const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component component, fmi2Boolean loggingOn,
                               size_t nCategories, const fmi2String categories[]) {
    INSTANCE("fmi2SetDebugLogging", ANY_MODE)
    (void)nCategories;
    (void)categories;
    c->m.debug_logging = loggingOn ? 1 : 0;
    return fmi2OK;
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation,
                              const fmi2CallbackFunctions *functions, fmi2Boolean visible,
                              fmi2Boolean loggingOn) {
    Fmi2Instance *c;
    char *name;
    size_t len;
    (void)fmuResourceLocation;
    (void)visible;
    if (functions == NULL || instanceName == NULL) return NULL;
    if (fmuGUID == NULL || strcmp(fmuGUID, MODEL_GUID) != 0) {
        if (functions->logger != NULL)
            functions->logger(functions->componentEnvironment, instanceName, fmi2Error,
                              "logStatusError", "GUID mismatch: this FMU is " MODEL_GUID);
        return NULL;
    }
    if (fmuType == fmi2ModelExchange && !MODEL_HAS_ME) return NULL;
    if (fmuType == fmi2CoSimulation && !MODEL_HAS_CS) return NULL;
    c = functions->allocateMemory != NULL ? functions->allocateMemory(1, sizeof(Fmi2Instance))
                                          : calloc(1, sizeof(Fmi2Instance));
    if (c == NULL) return NULL;
    len = strlen(instanceName) + 1;
    name = functions->allocateMemory != NULL ? functions->allocateMemory(len, 1)
                                             : calloc(len, 1);
    if (name == NULL) {
        if (functions->freeMemory != NULL) functions->freeMemory(c);
        else free(c);
        return NULL;
    }
    memcpy(name, instanceName, len);
    c->cb = *functions;
    c->m.instance_name = name;
    c->m.host = c;
    c->m.logger = fmi2_logger;
    c->m.debug_logging = loggingOn ? 1 : 0;
    bsm_reset(&c->m);
    c->m.s.is_cs = (fmuType == fmi2CoSimulation);
    c->m.s.mode = MODE_INSTANTIATED;
    return c;
}

void fmi2FreeInstance(fmi2Component component) {
    Fmi2Instance *c = (Fmi2Instance *)component;
    fmi2CallbackFreeMemory release;
    if (c == NULL) return;
    release = c->cb.freeMemory;
    if (release != NULL) {
        release((void *)c->m.instance_name);
        release(c);
    } else {
        free((void *)c->m.instance_name);
        free(c);
    }
}

fmi2Status fmi2SetupExperiment(fmi2Component component, fmi2Boolean toleranceDefined,
                               fmi2Real tolerance, fmi2Real startTime,
                               fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
    INSTANCE("fmi2SetupExperiment", MODE_INSTANTIATED)
    (void)stopTimeDefined;
    (void)stopTime;
    if (toleranceDefined) {
        if (!(tolerance > 0.0 && tolerance < 1.0)) {
            bsm_log(&c->m, BSM_ERROR, "logStatusError",
                    "tolerance must be in (0, 1), got %g", tolerance);
            return fmi2Error;
        }
        c->m.s.rtol = tolerance;
    }
    c->m.s.time = startTime;
    bsm_invalidate(&c->m);
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component component) {
    INSTANCE("fmi2EnterInitializationMode", MODE_INSTANTIATED)
    c->m.s.mode = MODE_INITIALIZATION;
    return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component component) {
    BsmStatus st;
    INSTANCE("fmi2ExitInitializationMode", MODE_INITIALIZATION)
    st = bsm_current_derivatives(&c->m);
    if (st == BSM_OK) st = bsm_current_outputs(&c->m);
    if (st != BSM_OK) return fail(c, st);
    c->m.s.mode = c->m.s.is_cs ? MODE_STEP_COMPLETE : MODE_EVENT;
    return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component component) {
    INSTANCE("fmi2Terminate", RUN_MODES | MODE_ERROR)
    if (c->m.s.is_cs) /* Model Exchange: the importer integrates, the stepper never ran */
        bsm_log(&c->m, BSM_OK, "logAll", "terminated at t = %g s after %ld internal steps "
                "(%ld rejected), %ld Jacobians, %ld LU factorisations", c->m.s.time,
                c->m.s.n_steps, c->m.s.n_rejected, c->m.s.n_jac, c->m.s.n_lu);
    c->m.s.mode = MODE_TERMINATED;
    return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component component) {
    int is_cs;
    INSTANCE("fmi2Reset", ANY_MODE)
    is_cs = c->m.s.is_cs;
    bsm_reset(&c->m);
    c->m.s.is_cs = is_cs;
    c->m.s.mode = MODE_INSTANTIATED;
    return fmi2OK;
}

/* ------------------------------------------------------------------ values */
static fmi2Status bad_vr(Fmi2Instance *c, fmi2ValueReference vr, const char *what) {
    bsm_log(&c->m, BSM_ERROR, "logStatusError", "%s: value reference %u is not valid", what,
            (unsigned)vr);
    return fmi2Error;
}

/* Map a shared operation's outcome to an FMI status. */
static fmi2Status outcome(Fmi2Instance *c, BsmCall call) {
    if (call == BSM_CALL_FAILED) return fail(c, BSM_ERROR);
    if (call == BSM_CALL_WARNED) return fmi2Warning;
    return call == BSM_CALL_DONE ? fmi2OK : fmi2Error;
}

fmi2Status fmi2GetReal(fmi2Component component, const fmi2ValueReference vr[], size_t nvr,
                       fmi2Real value[]) {
    size_t i;
    INSTANCE("fmi2GetReal", ANY_MODE)
    for (i = 0; i < nvr; ++i) {
        BsmStatus st;
        if (vr[i] >= VR_END) return bad_vr(c, vr[i], "fmi2GetReal");
        st = bsm_get_real(&c->m, vr[i], &value[i]);
        if (st != BSM_OK) return fail(c, st);
    }
    return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component component, const fmi2ValueReference vr[], size_t nvr,
                       const fmi2Real value[]) {
    size_t i;
    INSTANCE("fmi2SetReal", RUN_MODES | MODE_INSTANTIATED)
    for (i = 0; i < nvr; ++i) {
        BsmCall call = bsm_set_real(&c->m, vr[i], value[i], (c->m.s.mode & SETUP_MODES) != 0,
                                    (c->m.s.mode & TUNE_MODES) != 0, "fmi2SetReal");
        if (call != BSM_CALL_DONE) return outcome(c, call);
    }
    bsm_invalidate(&c->m);
    return fmi2OK;
}

fmi2Status fmi2GetInteger(fmi2Component component, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Integer value[]) {
    INSTANCE("fmi2GetInteger", ANY_MODE)
    (void)value;
    return nvr == 0 ? fmi2OK : bad_vr(c, vr[0], "fmi2GetInteger");
}

fmi2Status fmi2GetBoolean(fmi2Component component, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Boolean value[]) {
    INSTANCE("fmi2GetBoolean", ANY_MODE)
    (void)value;
    return nvr == 0 ? fmi2OK : bad_vr(c, vr[0], "fmi2GetBoolean");
}

fmi2Status fmi2GetString(fmi2Component component, const fmi2ValueReference vr[], size_t nvr,
                         fmi2String value[]) {
    INSTANCE("fmi2GetString", ANY_MODE)
    (void)value;
    return nvr == 0 ? fmi2OK : bad_vr(c, vr[0], "fmi2GetString");
}

fmi2Status fmi2SetInteger(fmi2Component component, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Integer value[]) {
    INSTANCE("fmi2SetInteger", ANY_MODE)
    (void)value;
    return nvr == 0 ? fmi2OK : bad_vr(c, vr[0], "fmi2SetInteger");
}

fmi2Status fmi2SetBoolean(fmi2Component component, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Boolean value[]) {
    INSTANCE("fmi2SetBoolean", ANY_MODE)
    (void)value;
    return nvr == 0 ? fmi2OK : bad_vr(c, vr[0], "fmi2SetBoolean");
}

fmi2Status fmi2SetString(fmi2Component component, const fmi2ValueReference vr[], size_t nvr,
                         const fmi2String value[]) {
    INSTANCE("fmi2SetString", ANY_MODE)
    (void)value;
    return nvr == 0 ? fmi2OK : bad_vr(c, vr[0], "fmi2SetString");
}

/* ------------------------------------------------------------------ FMU state */
fmi2Status fmi2GetFMUstate(fmi2Component component, fmi2FMUstate *state) {
    BsmState *copy;
    INSTANCE("fmi2GetFMUstate", ANY_MODE)
    copy = (BsmState *)*state;
    if (copy == NULL) {
        copy = c->cb.allocateMemory != NULL ? c->cb.allocateMemory(1, sizeof(BsmState))
                                            : calloc(1, sizeof(BsmState));
        if (copy == NULL) {
            bsm_log(&c->m, BSM_ERROR, "logStatusError", "out of memory");
            return fmi2Error;
        }
    }
    *copy = c->m.s;
    *state = copy;
    return fmi2OK;
}

fmi2Status fmi2SetFMUstate(fmi2Component component, fmi2FMUstate state) {
    INSTANCE("fmi2SetFMUstate", ANY_MODE)
    if (state == NULL) {
        bsm_log(&c->m, BSM_ERROR, "logStatusError", "fmi2SetFMUstate: no state given");
        return fmi2Error;
    }
    c->m.s = *(const BsmState *)state;
    bsm_invalidate(&c->m);
    return fmi2OK;
}

fmi2Status fmi2FreeFMUstate(fmi2Component component, fmi2FMUstate *state) {
    INSTANCE("fmi2FreeFMUstate", ANY_MODE)
    if (state != NULL && *state != NULL) {
        if (c->cb.freeMemory != NULL) c->cb.freeMemory(*state);
        else free(*state);
        *state = NULL;
    }
    return fmi2OK;
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component component, fmi2FMUstate state,
                                      size_t *size) {
    INSTANCE("fmi2SerializedFMUstateSize", ANY_MODE)
    (void)state;
    *size = bsm_serialized_size();
    return fmi2OK;
}

fmi2Status fmi2SerializeFMUstate(fmi2Component component, fmi2FMUstate state,
                                 fmi2Byte serializedState[], size_t size) {
    INSTANCE("fmi2SerializeFMUstate", ANY_MODE)
    return bsm_serialize(&c->m, (const BsmState *)state, SERIAL_MAGIC, serializedState, size,
                         "fmi2SerializeFMUstate") == BSM_OK ? fmi2OK : fmi2Error;
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component component, const fmi2Byte serializedState[],
                                   size_t size, fmi2FMUstate *state) {
    BsmState restored;
    fmi2FMUstate copy = NULL;
    INSTANCE("fmi2DeSerializeFMUstate", ANY_MODE)
    if (bsm_deserialize(&c->m, SERIAL_MAGIC, serializedState, size, &restored,
                        "fmi2DeSerializeFMUstate") != BSM_OK) {
        return fmi2Error;
    }
    if (fmi2GetFMUstate(component, &copy) != fmi2OK) return fmi2Error;
    *(BsmState *)copy = restored;
    *state = copy;
    return fmi2OK;
}

/* ------------------------------------------------------------------ directional derivatives */
fmi2Status fmi2GetDirectionalDerivative(fmi2Component component,
                                        const fmi2ValueReference vUnknown_ref[],
                                        size_t nUnknown, const fmi2ValueReference vKnown_ref[],
                                        size_t nKnown, const fmi2Real dvKnown[],
                                        fmi2Real dvUnknown[]) {
    INSTANCE("fmi2GetDirectionalDerivative", RUN_MODES)
    return outcome(c, bsm_directional_derivative(&c->m, vUnknown_ref, nUnknown, vKnown_ref,
                                                 nKnown, dvKnown, dvUnknown,
                                                 "fmi2GetDirectionalDerivative"));
}

/* ------------------------------------------------------------------ model exchange */
fmi2Status fmi2EnterEventMode(fmi2Component component) {
    INSTANCE("fmi2EnterEventMode", MODE_EVENT | MODE_CONTINUOUS)
    c->m.s.mode = MODE_EVENT;
    return fmi2OK;
}

fmi2Status fmi2NewDiscreteStates(fmi2Component component, fmi2EventInfo *info) {
    INSTANCE("fmi2NewDiscreteStates", MODE_EVENT)
    info->newDiscreteStatesNeeded = fmi2False;
    info->terminateSimulation = fmi2False;
    info->nominalsOfContinuousStatesChanged = fmi2False;
    info->valuesOfContinuousStatesChanged = fmi2False;
    info->nextEventTimeDefined = fmi2False;
    info->nextEventTime = 0.0;
    return fmi2OK;
}

fmi2Status fmi2EnterContinuousTimeMode(fmi2Component component) {
    INSTANCE("fmi2EnterContinuousTimeMode", MODE_EVENT)
    c->m.s.mode = MODE_CONTINUOUS;
    return fmi2OK;
}

fmi2Status fmi2CompletedIntegratorStep(fmi2Component component,
                                       fmi2Boolean noSetFMUStatePriorToCurrentPoint,
                                       fmi2Boolean *enterEventMode,
                                       fmi2Boolean *terminateSimulation) {
    INSTANCE("fmi2CompletedIntegratorStep", MODE_CONTINUOUS)
    (void)noSetFMUStatePriorToCurrentPoint;
    *enterEventMode = fmi2False;
    *terminateSimulation = fmi2False;
    return fmi2OK;
}

fmi2Status fmi2SetTime(fmi2Component component, fmi2Real time) {
    INSTANCE("fmi2SetTime", MODE_EVENT | MODE_CONTINUOUS)
    c->m.s.time = time;
    bsm_invalidate(&c->m);
    return fmi2OK;
}

fmi2Status fmi2SetContinuousStates(fmi2Component component, const fmi2Real x[], size_t nx) {
    size_t i;
    INSTANCE("fmi2SetContinuousStates", MODE_EVENT | MODE_CONTINUOUS)
    if (nx != NX) {
        bsm_log(&c->m, BSM_ERROR, "logStatusError",
                "fmi2SetContinuousStates: expected %d states, got %u", NX, (unsigned)nx);
        return fmi2Error;
    }
    for (i = 0; i < nx; ++i)
        if (!isfinite(x[i])) {
            bsm_log(&c->m, BSM_ERROR, "logStatusError",
                    "fmi2SetContinuousStates: %s is not finite at t = %g s",
                    bsm_x_names[i], c->m.s.time);
            return fail(c, BSM_ERROR);
        }
    memcpy(c->m.s.x, x, sizeof(double) * nx);
    bsm_invalidate(&c->m);
    return fmi2OK;
}

fmi2Status fmi2GetDerivatives(fmi2Component component, fmi2Real derivatives[], size_t nx) {
    BsmStatus st;
    INSTANCE("fmi2GetDerivatives", RUN_MODES | MODE_TERMINATED)
    if (nx != NX) {
        bsm_log(&c->m, BSM_ERROR, "logStatusError",
                "fmi2GetDerivatives: expected %d states, got %u", NX, (unsigned)nx);
        return fmi2Error;
    }
    st = bsm_current_derivatives(&c->m);
    if (st != BSM_OK) return fail(c, st);
    memcpy(derivatives, c->m.dx, sizeof(double) * nx);
    return fmi2OK;
}

fmi2Status fmi2GetEventIndicators(fmi2Component component, fmi2Real eventIndicators[],
                                  size_t ni) {
    INSTANCE("fmi2GetEventIndicators", ANY_MODE)
    (void)eventIndicators;
    return ni == 0 ? fmi2OK : bad_vr(c, (fmi2ValueReference)ni, "fmi2GetEventIndicators");
}

fmi2Status fmi2GetContinuousStates(fmi2Component component, fmi2Real x[], size_t nx) {
    INSTANCE("fmi2GetContinuousStates", ANY_MODE)
    if (nx != NX) {
        bsm_log(&c->m, BSM_ERROR, "logStatusError",
                "fmi2GetContinuousStates: expected %d states, got %u", NX, (unsigned)nx);
        return fmi2Error;
    }
    memcpy(x, c->m.s.x, sizeof(double) * nx);
    return fmi2OK;
}

fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component component, fmi2Real x_nominal[],
                                             size_t nx) {
    size_t i;
    INSTANCE("fmi2GetNominalsOfContinuousStates", ANY_MODE)
    for (i = 0; i < nx && i < NX; ++i) x_nominal[i] = bsm_x_nominal[i];
    return fmi2OK;
}

/* ------------------------------------------------------------------ co-simulation */
fmi2Status fmi2SetRealInputDerivatives(fmi2Component component, const fmi2ValueReference vr[],
                                       size_t nvr, const fmi2Integer order[],
                                       const fmi2Real value[]) {
    size_t i;
    INSTANCE("fmi2SetRealInputDerivatives", MODE_INITIALIZATION | MODE_STEP_COMPLETE)
    for (i = 0; i < nvr; ++i) {
        if (vr[i] < VR_U || vr[i] >= VR_Y || order[i] < 1 || order[i] > 3) {
            bsm_log(&c->m, BSM_ERROR, "logStatusError",
                    "fmi2SetRealInputDerivatives: derivatives of order 1 to 3 of inputs only "
                    "(got vr %u, order %d)", (unsigned)vr[i], (int)order[i]);
            return fmi2Error;
        }
        if (!isfinite(value[i])) {
            char num[32];
            bsm_log(&c->m, BSM_ERROR, "logStatusError",
                    "fmi2SetRealInputDerivatives: derivative of %s must be finite, got %s",
                    bsm_u_names[vr[i] - VR_U], bsm_num(num, value[i]));
            return fail(c, BSM_ERROR);
        }
        (order[i] == 1 ? c->m.s.du : order[i] == 2 ? c->m.s.d2u : c->m.s.d3u)[vr[i] - VR_U] =
            value[i];
    }
    return fmi2OK;
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component component, const fmi2ValueReference vr[],
                                        size_t nvr, const fmi2Integer order[],
                                        fmi2Real value[]) {
    INSTANCE("fmi2GetRealOutputDerivatives", ANY_MODE)
    return outcome(c, bsm_output_derivatives(&c->m, vr, nvr, order, value, /* fmi2Integer: int */
                                             "fmi2GetRealOutputDerivatives"));
}

fmi2Status fmi2DoStep(fmi2Component component, fmi2Real currentCommunicationPoint,
                      fmi2Real communicationStepSize,
                      fmi2Boolean noSetFMUStatePriorToCurrentPoint) {
    BsmStatus st;
    double t = 0.0;
    INSTANCE("fmi2DoStep", MODE_STEP_COMPLETE)
    (void)noSetFMUStatePriorToCurrentPoint;
    t = c->m.s.time;
    if (!(communicationStepSize > 0.0) || !isfinite(communicationStepSize) ||
        fabs(currentCommunicationPoint - t) > 1e-9 * fmax(1.0, fabs(t))) {
        bsm_log(&c->m, BSM_ERROR, "logStatusError",
                "fmi2DoStep: step from t = %.17g s with h = %g s, but the FMU is at t = %.17g s "
                "(h must be positive)", currentCommunicationPoint, communicationStepSize, t);
        return fmi2Error;
    }
    c->m.s.time = currentCommunicationPoint;
    st = bsm_do_step(&c->m, communicationStepSize);
    if (st != BSM_OK) return fail(c, st);
    return fmi2OK;
}

fmi2Status fmi2CancelStep(fmi2Component component) {
    INSTANCE("fmi2CancelStep", ANY_MODE)
    bsm_log(&c->m, BSM_ERROR, "logStatusError", "fmi2CancelStep: doStep is synchronous");
    return fmi2Error;
}

fmi2Status fmi2GetStatus(fmi2Component component, const fmi2StatusKind s, fmi2Status *value) {
    INSTANCE("fmi2GetStatus", ANY_MODE)
    if (s != fmi2DoStepStatus) return fmi2Discard;
    *value = fmi2OK;
    return fmi2OK;
}

fmi2Status fmi2GetRealStatus(fmi2Component component, const fmi2StatusKind s, fmi2Real *value) {
    INSTANCE("fmi2GetRealStatus", ANY_MODE)
    if (s != fmi2LastSuccessfulTime) return fmi2Discard;
    *value = c->m.s.time;
    return fmi2OK;
}

fmi2Status fmi2GetIntegerStatus(fmi2Component component, const fmi2StatusKind s,
                                fmi2Integer *value) {
    INSTANCE("fmi2GetIntegerStatus", ANY_MODE)
    (void)s;
    (void)value;
    return fmi2Discard;
}

fmi2Status fmi2GetBooleanStatus(fmi2Component component, const fmi2StatusKind s,
                                fmi2Boolean *value) {
    INSTANCE("fmi2GetBooleanStatus", ANY_MODE)
    if (s != fmi2Terminated) return fmi2Discard;
    *value = fmi2False;
    return fmi2OK;
}

fmi2Status fmi2GetStringStatus(fmi2Component component, const fmi2StatusKind s,
                               fmi2String *value) {
    INSTANCE("fmi2GetStringStatus", ANY_MODE)
    (void)s;
    (void)value;
    return fmi2Discard;
}
