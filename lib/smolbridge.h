/* smolbridge.h — umbrella header: includes every public module header. */
#ifndef SMOLBRIDGE_H
#define SMOLBRIDGE_H

#include <smolbridge/common.h>
#include <smolbridge/ini.h>
#include <smolbridge/rng.h>
#include <smolbridge/stats.h>
#include <smolbridge/passage.h>
#include <smolbridge/bridge.h>
#include <smolbridge/langevin.h>
#include <smolbridge/langevin_hit.h>
#include <smolbridge/langevin_shear.h>
#include <smolbridge/simulate.h>
#include <smolbridge/kernel.h>
#include <smolbridge/dlvo.h>
#include <smolbridge/pbe.h>
#include <smolbridge/engine.h>
#include <smolbridge/engine_bridge.h>
#include <smolbridge/engine_firsthit.h>
#include <smolbridge/engine_field.h>
#include <smolbridge/pgd.h>
#include <smolbridge/spray.h>
#include <smolbridge/validate.h>
#include <smolbridge/collide.h>

#endif /* SMOLBRIDGE_H */
