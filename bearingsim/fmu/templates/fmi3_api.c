/* bearingsim FMU runtime: the FMI 3.0 API (Model Exchange and Co-Simulation) on top of
 * bsm_model.h, the same FMI-independent runtime as fmi2_api.c. Generic: the model-specific part
 * is in model_config.h and model_data.c.
 *
 * Variables are float64 scalars in the value-reference blocks of model_config.h; the independent
 * variable `time` has the value reference VR_END. Co-simulation holds inputs constant over a
 * step unless the importer gives them between communication points by intermediate update: it
 * names the inputs in requiredIntermediateVariables and passes an intermediateUpdate callback;
 * the stepper then calls back at every time it evaluates the model inside fmi3DoStep (stage
 * times of tentative internal steps, so times may repeat or go back after a rejected step:
 * intermediateStepFinished = false) and the importer sets those inputs there. No event mode,
 * no early return, no intermediate outputs; Model Exchange has no events. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fmi3Functions.h"
#include "bsm_model.h"

typedef enum {
    MODE_INSTANTIATED = 1,
    MODE_INITIALIZATION = 2,
    MODE_EVENT = 4,
    MODE_CONTINUOUS = 8,
    MODE_STEP = 16,
    MODE_TERMINATED = 32,
    MODE_ERROR = 64,
    MODE_INTERMEDIATE = 128 /* inside the importer's intermediateUpdate callback */
} Mode;

#define ANY_MODE 0x7f
#define SETUP_MODES (MODE_INSTANTIATED | MODE_INITIALIZATION)
#define TUNE_MODES (SETUP_MODES | MODE_EVENT | MODE_STEP)
#define RUN_MODES (MODE_INITIALIZATION | MODE_EVENT | MODE_CONTINUOUS | MODE_STEP)

#define VR_TIME VR_END
#define SERIAL_MAGIC 0x42534d33u /* "BSM3" */

typedef struct {
    BsmInstance m;
    fmi3InstanceEnvironment env;
    fmi3LogMessageCallback log_message;
    /* intermediate update: the importer's callback, the inputs it sets inside a step
     * (requiredIntermediateVariables) and their values set last */
    fmi3IntermediateUpdateCallback intermediate_update;
    int n_between;
    unsigned char between[BSM_DIM(NU)];
    double u_between[BSM_DIM(NU)];
} Fmi3Instance;

static void fmi3_logger(void *host, BsmStatus status, const char *category,
                        const char *message) {
    Fmi3Instance *c = (Fmi3Instance *)host;
    if (c->log_message != NULL) c->log_message(c->env, (fmi3Status)status, category, message);
}

static fmi3Status check_mode(Fmi3Instance *c, int modes, const char *function) {
    if (c == NULL) return fmi3Error;
    if (c->m.s.mode & modes) return fmi3OK;
    bsm_log(&c->m, BSM_ERROR, "logStatusError", "%s must not be called in this state",
            function);
    return fmi3Error;
}

static fmi3Status fail(Fmi3Instance *c, BsmStatus st) {
    if (st == BSM_ERROR) c->m.s.mode = MODE_ERROR;
    return (fmi3Status)st;
}

static fmi3Status not_provided(Fmi3Instance *c, const char *function) {
    bsm_log(&c->m, BSM_ERROR, "logStatusError", "%s is not provided by this FMU", function);
    return fmi3Error;
}

#define INSTANCE(function, modes)                                         \
    Fmi3Instance *c = (Fmi3Instance *)instance;                          \
    if (check_mode(c, (modes), (function)) != fmi3OK) return fmi3Error;

/* ------------------------------------------------------------------ common functions */
const char *fmi3GetVersion(void) { return fmi3Version; }

fmi3Status fmi3SetDebugLogging(fmi3Instance instance, fmi3Boolean loggingOn, size_t nCategories,
                               const fmi3String categories[]) {
    INSTANCE("fmi3SetDebugLogging", ANY_MODE)
    (void)nCategories;
    (void)categories;
    c->m.debug_logging = loggingOn ? 1 : 0;
    return fmi3OK;
}

static Fmi3Instance *instantiate(fmi3String instanceName, fmi3String token, int is_cs,
                                 fmi3Boolean loggingOn, fmi3InstanceEnvironment env,
                                 fmi3LogMessageCallback log_message) {
    Fmi3Instance *c;
    char *name;
    size_t len;
    if (instanceName == NULL) return NULL;
    if (token == NULL || strcmp(token, MODEL_GUID) != 0) {
        if (log_message != NULL)
            log_message(env, fmi3Error, "logStatusError",
                        "instantiation token mismatch: this FMU is " MODEL_GUID);
        return NULL;
    }
    if ((is_cs && !MODEL_HAS_CS) || (!is_cs && !MODEL_HAS_ME)) {
        if (log_message != NULL)
            log_message(env, fmi3Error, "logStatusError",
                        is_cs ? "this FMU has no co-simulation interface"
                              : "this FMU has no model-exchange interface");
        return NULL;
    }
    c = (Fmi3Instance *)calloc(1, sizeof(Fmi3Instance));
    if (c == NULL) return NULL;
    len = strlen(instanceName) + 1;
    name = (char *)calloc(len, 1);
    if (name == NULL) {
        free(c);
        return NULL;
    }
    memcpy(name, instanceName, len);
    c->env = env;
    c->log_message = log_message;
    c->m.instance_name = name;
    c->m.host = c;
    c->m.logger = fmi3_logger;
    c->m.debug_logging = loggingOn ? 1 : 0;
    bsm_reset(&c->m);
    c->m.s.is_cs = is_cs;
    c->m.s.mode = MODE_INSTANTIATED;
    return c;
}

fmi3Instance fmi3InstantiateModelExchange(fmi3String instanceName, fmi3String instantiationToken,
                                          fmi3String resourcePath, fmi3Boolean visible,
                                          fmi3Boolean loggingOn,
                                          fmi3InstanceEnvironment instanceEnvironment,
                                          fmi3LogMessageCallback logMessage) {
    (void)resourcePath;
    (void)visible;
    return instantiate(instanceName, instantiationToken, 0, loggingOn, instanceEnvironment,
                       logMessage);
}

/* Inputs the importer sets between communication points (FMI 3.0 intermediate update): the
 * stepper asks for the inputs at each time t it evaluates the model; the importer sets those
 * in requiredIntermediateVariables in its callback; the others stay at their values of the
 * doStep start. Returns 1 (the inputs at t are in u). */
static int intermediate_inputs(void *host, double t, double *u) {
    Fmi3Instance *c = (Fmi3Instance *)host;
    fmi3Boolean early = fmi3False;
    fmi3Float64 early_time = t;
    int k, mode = c->m.s.mode;
    c->m.s.mode = MODE_INTERMEDIATE;
    c->intermediate_update(c->env, t, fmi3True, fmi3False, fmi3False, fmi3False, &early,
                           &early_time);
    c->m.s.mode = mode;
    for (k = 0; k < NU; ++k) u[k] = c->between[k] ? c->u_between[k] : c->m.saved.u[k];
    return 1;
}

/* Check and register requiredIntermediateVariables (inputs only: the FMU offers no
 * intermediate outputs). Returns 1 if usable. */
static int register_intermediate(Fmi3Instance *c, const fmi3ValueReference vrs[], size_t n,
                                 fmi3IntermediateUpdateCallback callback) {
    size_t i;
    if (n == 0) return 1;
    if (callback == NULL) {
        bsm_log(&c->m, BSM_ERROR, "logStatusError",
                "fmi3InstantiateCoSimulation: %u requiredIntermediateVariables but no "
                "intermediateUpdate callback", (unsigned)n);
        return 0;
    }
    for (i = 0; i < n; ++i) {
        if (vrs[i] < VR_U || vrs[i] >= VR_Y) {
            bsm_log(&c->m, BSM_ERROR, "logStatusError",
                    "fmi3InstantiateCoSimulation: requiredIntermediateVariables: value reference "
                    "%u is not an input (only inputs have intermediateUpdate=\"true\")",
                    (unsigned)vrs[i]);
            return 0;
        }
        if (!c->between[vrs[i] - VR_U]) c->n_between++;
        c->between[vrs[i] - VR_U] = 1;
    }
    c->intermediate_update = callback;
    c->m.inputs_between = intermediate_inputs;
    return 1;
}

fmi3Instance fmi3InstantiateCoSimulation(
    fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath,
    fmi3Boolean visible, fmi3Boolean loggingOn, fmi3Boolean eventModeUsed,
    fmi3Boolean earlyReturnAllowed, const fmi3ValueReference requiredIntermediateVariables[],
    size_t nRequiredIntermediateVariables, fmi3InstanceEnvironment instanceEnvironment,
    fmi3LogMessageCallback logMessage, fmi3IntermediateUpdateCallback intermediateUpdate) {
    (void)resourcePath;
    (void)visible;
    Fmi3Instance *c;
    (void)earlyReturnAllowed;
    if (eventModeUsed) {
        if (logMessage != NULL)
            logMessage(instanceEnvironment, fmi3Error, "logStatusError",
                       "this FMU has no event mode in co-simulation (hasEventMode=false)");
        return NULL;
    }
    c = instantiate(instanceName, instantiationToken, 1, loggingOn, instanceEnvironment,
                    logMessage);
    if (c != NULL && !register_intermediate(c, requiredIntermediateVariables,
                                            nRequiredIntermediateVariables, intermediateUpdate)) {
        fmi3FreeInstance(c);
        return NULL;
    }
    return c;
}

fmi3Instance fmi3InstantiateScheduledExecution(
    fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath,
    fmi3Boolean visible, fmi3Boolean loggingOn, fmi3InstanceEnvironment instanceEnvironment,
    fmi3LogMessageCallback logMessage, fmi3ClockUpdateCallback clockUpdate,
    fmi3LockPreemptionCallback lockPreemption, fmi3UnlockPreemptionCallback unlockPreemption) {
    (void)instanceName;
    (void)instantiationToken;
    (void)resourcePath;
    (void)visible;
    (void)loggingOn;
    (void)clockUpdate;
    (void)lockPreemption;
    (void)unlockPreemption;
    if (logMessage != NULL)
        logMessage(instanceEnvironment, fmi3Error, "logStatusError",
                   "scheduled execution is not provided by this FMU");
    return NULL;
}

void fmi3FreeInstance(fmi3Instance instance) {
    Fmi3Instance *c = (Fmi3Instance *)instance;
    if (c == NULL) return;
    free((void *)c->m.instance_name);
    free(c);
}

fmi3Status fmi3EnterInitializationMode(fmi3Instance instance, fmi3Boolean toleranceDefined,
                                       fmi3Float64 tolerance, fmi3Float64 startTime,
                                       fmi3Boolean stopTimeDefined, fmi3Float64 stopTime) {
    INSTANCE("fmi3EnterInitializationMode", MODE_INSTANTIATED)
    (void)stopTimeDefined;
    (void)stopTime;
    if (toleranceDefined) {
        if (!(tolerance > 0.0 && tolerance < 1.0)) {
            bsm_log(&c->m, BSM_ERROR, "logStatusError", "tolerance must be in (0, 1), got %g",
                    tolerance);
            return fmi3Error;
        }
        c->m.s.rtol = tolerance;
    }
    c->m.s.time = startTime;
    c->m.s.mode = MODE_INITIALIZATION;
    bsm_invalidate(&c->m);
    return fmi3OK;
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance instance) {
    BsmStatus st;
    INSTANCE("fmi3ExitInitializationMode", MODE_INITIALIZATION)
    st = bsm_current_derivatives(&c->m);
    if (st == BSM_OK) st = bsm_current_outputs(&c->m);
    if (st != BSM_OK) return fail(c, st);
    c->m.s.mode = c->m.s.is_cs ? MODE_STEP : MODE_EVENT;
    return fmi3OK;
}

fmi3Status fmi3EnterEventMode(fmi3Instance instance) {
    INSTANCE("fmi3EnterEventMode", MODE_EVENT | MODE_CONTINUOUS)
    c->m.s.mode = MODE_EVENT;
    return fmi3OK;
}

fmi3Status fmi3Terminate(fmi3Instance instance) {
    INSTANCE("fmi3Terminate", RUN_MODES | MODE_ERROR)
    if (c->m.s.is_cs) /* Model Exchange: the importer integrates, the stepper never ran */
        bsm_log(&c->m, BSM_OK, "logAll", "terminated at t = %g s after %ld internal steps "
                "(%ld rejected), %ld Jacobians, %ld LU factorisations", c->m.s.time,
                c->m.s.n_steps, c->m.s.n_rejected, c->m.s.n_jac, c->m.s.n_lu);
    c->m.s.mode = MODE_TERMINATED;
    return fmi3OK;
}

fmi3Status fmi3Reset(fmi3Instance instance) {
    int is_cs;
    INSTANCE("fmi3Reset", ANY_MODE)
    is_cs = c->m.s.is_cs;
    bsm_reset(&c->m);
    c->m.s.is_cs = is_cs;
    c->m.s.mode = MODE_INSTANTIATED;
    return fmi3OK;
}

/* ------------------------------------------------------------------ values */
static fmi3Status bad_vr(Fmi3Instance *c, fmi3ValueReference vr, const char *what) {
    bsm_log(&c->m, BSM_ERROR, "logStatusError", "%s: value reference %u is not valid", what,
            (unsigned)vr);
    return fmi3Error;
}

/* Map a shared operation's outcome to an FMI status. */
static fmi3Status outcome(Fmi3Instance *c, BsmCall call) {
    if (call == BSM_CALL_FAILED) return fail(c, BSM_ERROR);
    if (call == BSM_CALL_WARNED) return fmi3Warning;
    return call == BSM_CALL_DONE ? fmi3OK : fmi3Error;
}

static fmi3Status count_mismatch(Fmi3Instance *c, const char *function, size_t n_values,
                                 size_t n_refs) {
    bsm_log(&c->m, BSM_ERROR, "logStatusError", "%s: %u values for %u scalar variables",
            function, (unsigned)n_values, (unsigned)n_refs);
    return fmi3Error;
}

fmi3Status fmi3GetFloat64(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, fmi3Float64 values[], size_t nValues) {
    size_t i;
    INSTANCE("fmi3GetFloat64", ANY_MODE)
    if (nValues != nValueReferences)
        return count_mismatch(c, "fmi3GetFloat64", nValues, nValueReferences);
    for (i = 0; i < nValueReferences; ++i) {
        unsigned int r = valueReferences[i];
        BsmStatus st;
        if (r == VR_TIME) {
            values[i] = c->m.s.time;
            continue;
        }
        if (r >= VR_END) return bad_vr(c, r, "fmi3GetFloat64");
        st = bsm_get_real(&c->m, r, &values[i]);
        if (st != BSM_OK) return fail(c, st);
    }
    return fmi3OK;
}

/* fmi3SetFloat64 in intermediate update mode: inputs of requiredIntermediateVariables only,
 * each finite and in its range; a refused value leaves the instance as it was. */
static fmi3Status set_intermediate(Fmi3Instance *c, const fmi3ValueReference vrs[], size_t n,
                                   const fmi3Float64 values[]) {
    size_t i;
    fmi3Status warned = fmi3OK;
    BsmStatus st;
    for (i = 0; i < n; ++i) {
        unsigned int r = vrs[i];
        if (r < VR_U || r >= VR_Y || !c->between[r - VR_U]) {
            bsm_log(&c->m, BSM_ERROR, "logStatusError",
                    "fmi3SetFloat64 in intermediate update mode: value reference %u is not an "
                    "input named in requiredIntermediateVariables", r);
            return fmi3Error;
        }
        st = bsm_check_input(&c->m, (int)(r - VR_U), values[i]);
        if (st == BSM_ERROR) return fmi3Error;
        if (st == BSM_WARNING) warned = fmi3Warning;
    }
    for (i = 0; i < n; ++i) c->u_between[vrs[i] - VR_U] = values[i];
    return warned;
}

fmi3Status fmi3SetFloat64(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, const fmi3Float64 values[], size_t nValues) {
    size_t i;
    BsmCall warned = BSM_CALL_DONE;
    INSTANCE("fmi3SetFloat64", RUN_MODES | MODE_INSTANTIATED | MODE_INTERMEDIATE)
    if (nValues != nValueReferences)
        return count_mismatch(c, "fmi3SetFloat64", nValues, nValueReferences);
    if (c->m.s.mode == MODE_INTERMEDIATE)
        return set_intermediate(c, valueReferences, nValueReferences, values);
    for (i = 0; i < nValueReferences; ++i) {
        BsmCall call = bsm_set_real(&c->m, valueReferences[i], values[i],
                                    (c->m.s.mode & SETUP_MODES) != 0,
                                    (c->m.s.mode & TUNE_MODES) != 0, "fmi3SetFloat64");
        if (call == BSM_CALL_WARNED) warned = call;
        else if (call != BSM_CALL_DONE) return outcome(c, call);
    }
    bsm_invalidate(&c->m);
    return outcome(c, warned);
}

/* The FMU has float64 variables only: other types accept empty requests. */
#define NO_GETTER(NAME, TYPE)                                                                \
    fmi3Status NAME(fmi3Instance instance, const fmi3ValueReference valueReferences[],       \
                    size_t nValueReferences, TYPE values[], size_t nValues) {                \
        INSTANCE(#NAME, ANY_MODE)                                                            \
        (void)values;                                                                        \
        (void)nValues;                                                                       \
        return nValueReferences == 0 ? fmi3OK : bad_vr(c, valueReferences[0], #NAME);       \
    }
#define NO_SETTER(NAME, TYPE)                                                                \
    fmi3Status NAME(fmi3Instance instance, const fmi3ValueReference valueReferences[],       \
                    size_t nValueReferences, const TYPE values[], size_t nValues) {          \
        INSTANCE(#NAME, ANY_MODE)                                                            \
        (void)values;                                                                        \
        (void)nValues;                                                                       \
        return nValueReferences == 0 ? fmi3OK : bad_vr(c, valueReferences[0], #NAME);       \
    }

NO_GETTER(fmi3GetFloat32, fmi3Float32)
NO_GETTER(fmi3GetInt8, fmi3Int8)
NO_GETTER(fmi3GetUInt8, fmi3UInt8)
NO_GETTER(fmi3GetInt16, fmi3Int16)
NO_GETTER(fmi3GetUInt16, fmi3UInt16)
NO_GETTER(fmi3GetInt32, fmi3Int32)
NO_GETTER(fmi3GetUInt32, fmi3UInt32)
NO_GETTER(fmi3GetInt64, fmi3Int64)
NO_GETTER(fmi3GetUInt64, fmi3UInt64)
NO_GETTER(fmi3GetBoolean, fmi3Boolean)
NO_GETTER(fmi3GetString, fmi3String)
NO_SETTER(fmi3SetFloat32, fmi3Float32)
NO_SETTER(fmi3SetInt8, fmi3Int8)
NO_SETTER(fmi3SetUInt8, fmi3UInt8)
NO_SETTER(fmi3SetInt16, fmi3Int16)
NO_SETTER(fmi3SetUInt16, fmi3UInt16)
NO_SETTER(fmi3SetInt32, fmi3Int32)
NO_SETTER(fmi3SetUInt32, fmi3UInt32)
NO_SETTER(fmi3SetInt64, fmi3Int64)
NO_SETTER(fmi3SetUInt64, fmi3UInt64)
NO_SETTER(fmi3SetBoolean, fmi3Boolean)
NO_SETTER(fmi3SetString, fmi3String)

fmi3Status fmi3GetBinary(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, size_t valueSizes[], fmi3Binary values[],
                         size_t nValues) {
    INSTANCE("fmi3GetBinary", ANY_MODE)
    (void)valueSizes;
    (void)values;
    (void)nValues;
    return nValueReferences == 0 ? fmi3OK : bad_vr(c, valueReferences[0], "fmi3GetBinary");
}

fmi3Status fmi3SetBinary(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, const size_t valueSizes[],
                         const fmi3Binary values[], size_t nValues) {
    INSTANCE("fmi3SetBinary", ANY_MODE)
    (void)valueSizes;
    (void)values;
    (void)nValues;
    return nValueReferences == 0 ? fmi3OK : bad_vr(c, valueReferences[0], "fmi3SetBinary");
}

fmi3Status fmi3GetClock(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, fmi3Clock values[]) {
    INSTANCE("fmi3GetClock", ANY_MODE)
    (void)values;
    return nValueReferences == 0 ? fmi3OK : bad_vr(c, valueReferences[0], "fmi3GetClock");
}

fmi3Status fmi3SetClock(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, const fmi3Clock values[]) {
    INSTANCE("fmi3SetClock", ANY_MODE)
    (void)values;
    return nValueReferences == 0 ? fmi3OK : bad_vr(c, valueReferences[0], "fmi3SetClock");
}

/* ------------------------------------------------------------------ dependencies */
fmi3Status fmi3GetNumberOfVariableDependencies(fmi3Instance instance,
                                               fmi3ValueReference valueReference,
                                               size_t *nDependencies) {
    INSTANCE("fmi3GetNumberOfVariableDependencies", ANY_MODE)
    (void)valueReference;
    (void)nDependencies;
    return not_provided(c, "fmi3GetNumberOfVariableDependencies (see the ModelStructure)");
}

fmi3Status fmi3GetVariableDependencies(fmi3Instance instance, fmi3ValueReference dependent,
                                       size_t elementIndicesOfDependent[],
                                       fmi3ValueReference independents[],
                                       size_t elementIndicesOfIndependents[],
                                       fmi3DependencyKind dependencyKinds[],
                                       size_t nDependencies) {
    INSTANCE("fmi3GetVariableDependencies", ANY_MODE)
    (void)dependent;
    (void)elementIndicesOfDependent;
    (void)independents;
    (void)elementIndicesOfIndependents;
    (void)dependencyKinds;
    (void)nDependencies;
    return not_provided(c, "fmi3GetVariableDependencies (see the ModelStructure)");
}

/* ------------------------------------------------------------------ FMU state */
fmi3Status fmi3GetFMUState(fmi3Instance instance, fmi3FMUState *FMUState) {
    BsmState *copy;
    INSTANCE("fmi3GetFMUState", ANY_MODE)
    copy = (BsmState *)*FMUState;
    if (copy == NULL) {
        copy = (BsmState *)calloc(1, sizeof(BsmState));
        if (copy == NULL) {
            bsm_log(&c->m, BSM_ERROR, "logStatusError", "out of memory");
            return fmi3Error;
        }
    }
    *copy = c->m.s;
    *FMUState = copy;
    return fmi3OK;
}

fmi3Status fmi3SetFMUState(fmi3Instance instance, fmi3FMUState FMUState) {
    INSTANCE("fmi3SetFMUState", ANY_MODE)
    if (FMUState == NULL) {
        bsm_log(&c->m, BSM_ERROR, "logStatusError", "fmi3SetFMUState: no state given");
        return fmi3Error;
    }
    c->m.s = *(const BsmState *)FMUState;
    bsm_invalidate(&c->m);
    return fmi3OK;
}

fmi3Status fmi3FreeFMUState(fmi3Instance instance, fmi3FMUState *FMUState) {
    INSTANCE("fmi3FreeFMUState", ANY_MODE)
    if (FMUState != NULL && *FMUState != NULL) {
        free(*FMUState);
        *FMUState = NULL;
    }
    return fmi3OK;
}

fmi3Status fmi3SerializedFMUStateSize(fmi3Instance instance, fmi3FMUState FMUState,
                                      size_t *size) {
    INSTANCE("fmi3SerializedFMUStateSize", ANY_MODE)
    (void)FMUState;
    *size = bsm_serialized_size();
    return fmi3OK;
}

fmi3Status fmi3SerializeFMUState(fmi3Instance instance, fmi3FMUState FMUState,
                                 fmi3Byte serializedState[], size_t size) {
    INSTANCE("fmi3SerializeFMUState", ANY_MODE)
    return bsm_serialize(&c->m, (const BsmState *)FMUState, SERIAL_MAGIC, serializedState, size,
                         "fmi3SerializeFMUState") == BSM_OK ? fmi3OK : fmi3Error;
}

fmi3Status fmi3DeserializeFMUState(fmi3Instance instance, const fmi3Byte serializedState[],
                                   size_t size, fmi3FMUState *FMUState) {
    BsmState restored;
    fmi3FMUState copy = NULL;
    INSTANCE("fmi3DeserializeFMUState", ANY_MODE)
    if (bsm_deserialize(&c->m, SERIAL_MAGIC, serializedState, size, &restored,
                        "fmi3DeserializeFMUState") != BSM_OK) {
        return fmi3Error;
    }
    if (fmi3GetFMUState(instance, &copy) != fmi3OK) return fmi3Error;
    *(BsmState *)copy = restored;
    *FMUState = copy;
    return fmi3OK;
}

/* ------------------------------------------------------------------ partial derivatives */
fmi3Status fmi3GetDirectionalDerivative(fmi3Instance instance,
                                        const fmi3ValueReference unknowns[], size_t nUnknowns,
                                        const fmi3ValueReference knowns[], size_t nKnowns,
                                        const fmi3Float64 seed[], size_t nSeed,
                                        fmi3Float64 sensitivity[], size_t nSensitivity) {
    INSTANCE("fmi3GetDirectionalDerivative", RUN_MODES)
    if (nSeed != nKnowns || nSensitivity != nUnknowns) {
        bsm_log(&c->m, BSM_ERROR, "logStatusError",
                "fmi3GetDirectionalDerivative: %u seeds for %u knowns, %u sensitivities for %u "
                "unknowns", (unsigned)nSeed, (unsigned)nKnowns, (unsigned)nSensitivity,
                (unsigned)nUnknowns);
        return fmi3Error;
    }
    return outcome(c, bsm_directional_derivative(&c->m, unknowns, nUnknowns, knowns, nKnowns,
                                                 seed, sensitivity,
                                                 "fmi3GetDirectionalDerivative"));
}

fmi3Status fmi3GetAdjointDerivative(fmi3Instance instance, const fmi3ValueReference unknowns[],
                                    size_t nUnknowns, const fmi3ValueReference knowns[],
                                    size_t nKnowns, const fmi3Float64 seed[], size_t nSeed,
                                    fmi3Float64 sensitivity[], size_t nSensitivity) {
    INSTANCE("fmi3GetAdjointDerivative", ANY_MODE)
    (void)unknowns;
    (void)nUnknowns;
    (void)knowns;
    (void)nKnowns;
    (void)seed;
    (void)nSeed;
    (void)sensitivity;
    (void)nSensitivity;
    return not_provided(c, "fmi3GetAdjointDerivative");
}

/* ------------------------------------------------------------------ configuration, clocks */
fmi3Status fmi3EnterConfigurationMode(fmi3Instance instance) {
    INSTANCE("fmi3EnterConfigurationMode", ANY_MODE)
    return not_provided(c, "fmi3EnterConfigurationMode (no structural parameters)");
}

fmi3Status fmi3ExitConfigurationMode(fmi3Instance instance) {
    INSTANCE("fmi3ExitConfigurationMode", ANY_MODE)
    return not_provided(c, "fmi3ExitConfigurationMode (no structural parameters)");
}

fmi3Status fmi3GetIntervalDecimal(fmi3Instance instance,
                                  const fmi3ValueReference valueReferences[],
                                  size_t nValueReferences, fmi3Float64 intervals[],
                                  fmi3IntervalQualifier qualifiers[]) {
    INSTANCE("fmi3GetIntervalDecimal", ANY_MODE)
    (void)valueReferences;
    (void)nValueReferences;
    (void)intervals;
    (void)qualifiers;
    return not_provided(c, "fmi3GetIntervalDecimal (no clocks)");
}

fmi3Status fmi3GetIntervalFraction(fmi3Instance instance,
                                   const fmi3ValueReference valueReferences[],
                                   size_t nValueReferences, fmi3UInt64 counters[],
                                   fmi3UInt64 resolutions[], fmi3IntervalQualifier qualifiers[]) {
    INSTANCE("fmi3GetIntervalFraction", ANY_MODE)
    (void)valueReferences;
    (void)nValueReferences;
    (void)counters;
    (void)resolutions;
    (void)qualifiers;
    return not_provided(c, "fmi3GetIntervalFraction (no clocks)");
}

fmi3Status fmi3GetShiftDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                               size_t nValueReferences, fmi3Float64 shifts[]) {
    INSTANCE("fmi3GetShiftDecimal", ANY_MODE)
    (void)valueReferences;
    (void)nValueReferences;
    (void)shifts;
    return not_provided(c, "fmi3GetShiftDecimal (no clocks)");
}

fmi3Status fmi3GetShiftFraction(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                size_t nValueReferences, fmi3UInt64 counters[],
                                fmi3UInt64 resolutions[]) {
    INSTANCE("fmi3GetShiftFraction", ANY_MODE)
    (void)valueReferences;
    (void)nValueReferences;
    (void)counters;
    (void)resolutions;
    return not_provided(c, "fmi3GetShiftFraction (no clocks)");
}

fmi3Status fmi3SetIntervalDecimal(fmi3Instance instance,
                                  const fmi3ValueReference valueReferences[],
                                  size_t nValueReferences, const fmi3Float64 intervals[]) {
    INSTANCE("fmi3SetIntervalDecimal", ANY_MODE)
    (void)valueReferences;
    (void)nValueReferences;
    (void)intervals;
    return not_provided(c, "fmi3SetIntervalDecimal (no clocks)");
}

fmi3Status fmi3SetIntervalFraction(fmi3Instance instance,
                                   const fmi3ValueReference valueReferences[],
                                   size_t nValueReferences, const fmi3UInt64 counters[],
                                   const fmi3UInt64 resolutions[]) {
    INSTANCE("fmi3SetIntervalFraction", ANY_MODE)
    (void)valueReferences;
    (void)nValueReferences;
    (void)counters;
    (void)resolutions;
    return not_provided(c, "fmi3SetIntervalFraction (no clocks)");
}

fmi3Status fmi3SetShiftDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                               size_t nValueReferences, const fmi3Float64 shifts[]) {
    INSTANCE("fmi3SetShiftDecimal", ANY_MODE)
    (void)valueReferences;
    (void)nValueReferences;
    (void)shifts;
    return not_provided(c, "fmi3SetShiftDecimal (no clocks)");
}

fmi3Status fmi3SetShiftFraction(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                size_t nValueReferences, const fmi3UInt64 counters[],
                                const fmi3UInt64 resolutions[]) {
    INSTANCE("fmi3SetShiftFraction", ANY_MODE)
    (void)valueReferences;
    (void)nValueReferences;
    (void)counters;
    (void)resolutions;
    return not_provided(c, "fmi3SetShiftFraction (no clocks)");
}

fmi3Status fmi3EvaluateDiscreteStates(fmi3Instance instance) {
    INSTANCE("fmi3EvaluateDiscreteStates", RUN_MODES)
    return fmi3OK; /* no discrete states */
}

fmi3Status fmi3UpdateDiscreteStates(fmi3Instance instance, fmi3Boolean *discreteStatesNeedUpdate,
                                    fmi3Boolean *terminateSimulation,
                                    fmi3Boolean *nominalsOfContinuousStatesChanged,
                                    fmi3Boolean *valuesOfContinuousStatesChanged,
                                    fmi3Boolean *nextEventTimeDefined,
                                    fmi3Float64 *nextEventTime) {
    INSTANCE("fmi3UpdateDiscreteStates", MODE_EVENT)
    *discreteStatesNeedUpdate = fmi3False;
    *terminateSimulation = fmi3False;
    *nominalsOfContinuousStatesChanged = fmi3False;
    *valuesOfContinuousStatesChanged = fmi3False;
    *nextEventTimeDefined = fmi3False;
    *nextEventTime = 0.0;
    return fmi3OK;
}

/* ------------------------------------------------------------------ model exchange */
fmi3Status fmi3EnterContinuousTimeMode(fmi3Instance instance) {
    INSTANCE("fmi3EnterContinuousTimeMode", MODE_EVENT)
    c->m.s.mode = MODE_CONTINUOUS;
    return fmi3OK;
}

fmi3Status fmi3CompletedIntegratorStep(fmi3Instance instance,
                                       fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                                       fmi3Boolean *enterEventMode,
                                       fmi3Boolean *terminateSimulation) {
    INSTANCE("fmi3CompletedIntegratorStep", MODE_CONTINUOUS)
    (void)noSetFMUStatePriorToCurrentPoint;
    *enterEventMode = fmi3False;
    *terminateSimulation = fmi3False;
    return fmi3OK;
}

fmi3Status fmi3SetTime(fmi3Instance instance, fmi3Float64 time) {
    INSTANCE("fmi3SetTime", MODE_EVENT | MODE_CONTINUOUS)
    c->m.s.time = time;
    bsm_invalidate(&c->m);
    return fmi3OK;
}

fmi3Status fmi3SetContinuousStates(fmi3Instance instance, const fmi3Float64 continuousStates[],
                                   size_t nContinuousStates) {
    size_t i;
    INSTANCE("fmi3SetContinuousStates", MODE_EVENT | MODE_CONTINUOUS)
    if (nContinuousStates != NX) {
        bsm_log(&c->m, BSM_ERROR, "logStatusError",
                "fmi3SetContinuousStates: expected %d states, got %u", NX,
                (unsigned)nContinuousStates);
        return fmi3Error;
    }
    for (i = 0; i < nContinuousStates; ++i)
        if (!isfinite(continuousStates[i])) {
            bsm_log(&c->m, BSM_ERROR, "logStatusError",
                    "fmi3SetContinuousStates: %s is not finite at t = %g s", bsm_x_names[i],
                    c->m.s.time);
            return fail(c, BSM_ERROR);
        }
    memcpy(c->m.s.x, continuousStates, sizeof(double) * nContinuousStates);
    bsm_invalidate(&c->m);
    return fmi3OK;
}

fmi3Status fmi3GetContinuousStateDerivatives(fmi3Instance instance, fmi3Float64 derivatives[],
                                             size_t nContinuousStates) {
    BsmStatus st;
    INSTANCE("fmi3GetContinuousStateDerivatives", RUN_MODES | MODE_TERMINATED)
    if (nContinuousStates != NX) {
        bsm_log(&c->m, BSM_ERROR, "logStatusError",
                "fmi3GetContinuousStateDerivatives: expected %d states, got %u", NX,
                (unsigned)nContinuousStates);
        return fmi3Error;
    }
    st = bsm_current_derivatives(&c->m);
    if (st != BSM_OK) return fail(c, st);
    memcpy(derivatives, c->m.dx, sizeof(double) * nContinuousStates);
    return fmi3OK;
}

fmi3Status fmi3GetEventIndicators(fmi3Instance instance, fmi3Float64 eventIndicators[],
                                  size_t nEventIndicators) {
    INSTANCE("fmi3GetEventIndicators", ANY_MODE)
    (void)eventIndicators;
    return nEventIndicators == 0 ? fmi3OK : not_provided(c, "fmi3GetEventIndicators (none)");
}

fmi3Status fmi3GetContinuousStates(fmi3Instance instance, fmi3Float64 continuousStates[],
                                   size_t nContinuousStates) {
    INSTANCE("fmi3GetContinuousStates", ANY_MODE)
    if (nContinuousStates != NX) {
        bsm_log(&c->m, BSM_ERROR, "logStatusError",
                "fmi3GetContinuousStates: expected %d states, got %u", NX,
                (unsigned)nContinuousStates);
        return fmi3Error;
    }
    memcpy(continuousStates, c->m.s.x, sizeof(double) * nContinuousStates);
    return fmi3OK;
}

fmi3Status fmi3GetNominalsOfContinuousStates(fmi3Instance instance, fmi3Float64 nominals[],
                                             size_t nContinuousStates) {
    size_t i;
    INSTANCE("fmi3GetNominalsOfContinuousStates", ANY_MODE)
    for (i = 0; i < nContinuousStates && i < NX; ++i) nominals[i] = bsm_x_nominal[i];
    return fmi3OK;
}

fmi3Status fmi3GetNumberOfEventIndicators(fmi3Instance instance, size_t *nEventIndicators) {
    INSTANCE("fmi3GetNumberOfEventIndicators", ANY_MODE)
    *nEventIndicators = 0;
    return fmi3OK;
}

fmi3Status fmi3GetNumberOfContinuousStates(fmi3Instance instance, size_t *nContinuousStates) {
    INSTANCE("fmi3GetNumberOfContinuousStates", ANY_MODE)
    *nContinuousStates = NX;
    return fmi3OK;
}

/* ------------------------------------------------------------------ co-simulation */
fmi3Status fmi3EnterStepMode(fmi3Instance instance) {
    INSTANCE("fmi3EnterStepMode", ANY_MODE)
    return not_provided(c, "fmi3EnterStepMode (no event mode in co-simulation)");
}

fmi3Status fmi3GetOutputDerivatives(fmi3Instance instance,
                                    const fmi3ValueReference valueReferences[],
                                    size_t nValueReferences, const fmi3Int32 orders[],
                                    fmi3Float64 values[], size_t nValues) {
    INSTANCE("fmi3GetOutputDerivatives", ANY_MODE)
    if (nValues != nValueReferences)
        return count_mismatch(c, "fmi3GetOutputDerivatives", nValues, nValueReferences);
    return outcome(c, bsm_output_derivatives(&c->m, valueReferences, nValueReferences, orders,
                                             values, "fmi3GetOutputDerivatives"));
}

/* Before a step with intermediate inputs: their mean slope over the step, from the values the
 * importer gives at its end, for the stepper's df/dt (the stage values come from the importer
 * at each stage time). */
static void intermediate_slopes(Fmi3Instance *c, double h) {
    int k;
    double u_end[BSM_DIM(NU)];
    c->m.saved = c->m.s; /* inputs not set in the callback stay at those of the step start */
    memcpy(c->u_between, c->m.s.u, sizeof(c->u_between));
    intermediate_inputs(c, c->m.s.time + h, u_end);
    for (k = 0; k < NU; ++k)
        if (c->between[k]) c->m.s.du[k] = (u_end[k] - c->m.s.u[k]) / h;
}

fmi3Status fmi3DoStep(fmi3Instance instance, fmi3Float64 currentCommunicationPoint,
                      fmi3Float64 communicationStepSize,
                      fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                      fmi3Boolean *eventHandlingNeeded, fmi3Boolean *terminateSimulation,
                      fmi3Boolean *earlyReturn, fmi3Float64 *lastSuccessfulTime) {
    BsmStatus st;
    double t;
    INSTANCE("fmi3DoStep", MODE_STEP)
    (void)noSetFMUStatePriorToCurrentPoint;
    *eventHandlingNeeded = fmi3False;
    *terminateSimulation = fmi3False;
    *earlyReturn = fmi3False;
    t = c->m.s.time;
    *lastSuccessfulTime = t;
    if (!(communicationStepSize > 0.0) || !isfinite(communicationStepSize) ||
        fabs(currentCommunicationPoint - t) > 1e-9 * fmax(1.0, fabs(t))) {
        bsm_log(&c->m, BSM_ERROR, "logStatusError",
                "fmi3DoStep: step from t = %.17g s with h = %g s, but the FMU is at t = %.17g s "
                "(h must be positive)", currentCommunicationPoint, communicationStepSize, t);
        return fmi3Error;
    }
    c->m.s.time = currentCommunicationPoint;
    if (c->n_between > 0) intermediate_slopes(c, communicationStepSize);
    st = bsm_do_step(&c->m, communicationStepSize);
    *lastSuccessfulTime = c->m.s.time;
    if (st != BSM_OK) return fail(c, st);
    return fmi3OK;
}

fmi3Status fmi3ActivateModelPartition(fmi3Instance instance, fmi3ValueReference clockReference,
                                      fmi3Float64 activationTime) {
    INSTANCE("fmi3ActivateModelPartition", ANY_MODE)
    (void)clockReference;
    (void)activationTime;
    return not_provided(c, "fmi3ActivateModelPartition (no scheduled execution)");
}
