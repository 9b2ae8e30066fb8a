// OCCT's signal handlers, so that a fault inside OCCT becomes a Standard_Failure.
#include <OSD.hxx>

#include "base/internal.hpp"

namespace sweep::occt {

void install_signal_handlers(bool replace_existing) {
  // Floating point traps stay off (OCCT's algorithms rely on quiet infinities).
  OSD::SetSignal(replace_existing ? OSD_SignalMode_Set : OSD_SignalMode_SetUnhandled, false);
}

}  // namespace sweep::occt
