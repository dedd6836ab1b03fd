/* ref_ocean: see ref_ocean.h (being written). */
#include "ref_ocean.h"
