/* zscan — error reporting: the public zscan/error.h, under the name the
 * code base has always included. */
#ifndef ZS_ERROR_H
#define ZS_ERROR_H

#include "zscan/error.h"

#endif
