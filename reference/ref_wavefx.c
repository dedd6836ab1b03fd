/* ref_wavefx: see ref_wavefx.h (being written). */
#include "ref_wavefx.h"
