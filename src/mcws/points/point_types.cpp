// The WorkspacePoint registration compiles here once, so a broken field list fails the build of
// the library rather than of its first user.
#include "mcws/points/point_types.h"

static_assert(sizeof(mcws::WorkspacePoint) % 16 == 0, "WorkspacePoint must stay 16-byte aligned");
static_assert(sizeof(mcws::QualityPoint) % 16 == 0, "QualityPoint must stay 16-byte aligned");
