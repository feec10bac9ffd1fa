/* bearingsim FMU build: bind the libm functions that glibc 2.29 gave new symbol versions (exp,
 * exp2, log, log2, pow: faster implementations, same results within 1 ulp) to their original
 * x86-64 version GLIBC_2.2.5, so the binary loads on glibc 2.17 and later (manylinux2014,
 * RHEL 7/8, Ubuntu 18.04).
 *
 * Force-included (gcc -include) into every file of the binary that bearingsim ships; not part
 * of the FMU's sources: a rebuild from sources targets the glibc of the machine it runs on.
 * bearingsim.fmu.build.glibc_versions checks the result after every link. */
#ifndef BSM_GLIBC_2_17_H
#define BSM_GLIBC_2_17_H
#if defined(__linux__) && defined(__x86_64__)
#include <features.h>
#if defined(__GLIBC__)
__asm__(".symver exp,exp@GLIBC_2.2.5");
__asm__(".symver exp2,exp2@GLIBC_2.2.5");
__asm__(".symver log,log@GLIBC_2.2.5");
__asm__(".symver log2,log2@GLIBC_2.2.5");
__asm__(".symver pow,pow@GLIBC_2.2.5");
#endif
#endif
#endif
