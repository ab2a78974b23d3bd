// Not compiled: the layering test checks this file as if it lay in scanner/, where an include
// of report/ points up the chain and must be refused.
#pragma once

#include "report/report.h"
