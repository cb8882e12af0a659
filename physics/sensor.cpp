// Sensors: overlaps from the step's end transforms, and visitors swept through within it.
#include "physics/collide.h"
#include "physics/world.h"
#include "physics/world_state.h"

namespace rc {

void WorldState::destroySensorPair(std::size_t index, bool destroyed) {
  SensorPair& sp = sensorPairs_[index];
  if (sp.overlapping && wantsSensorEvents(sp))
    sensorSink().end.push_back({ref(sp.sensor), ref(sp.visitor), destroyed});
  sensorIndex_.erase(pairKey(sp.sensor, sp.visitor));
  if (index + 1 != sensorPairs_.size()) {
    sensorPairs_[index] = sensorPairs_.back();
    sensorIndex_[pairKey(sensorPairs_[index].sensor, sensorPairs_[index].visitor)] =
        static_cast<std::int32_t>(index);
  }
  sensorPairs_.pop_back();
}

void WorldState::updateSensors() {
  // Runs after the refit: transforms are the step's end; the awake bodies' slots still hold
  // where they started (startCenter_, startAngle_).
  for (std::size_t k = sensorPairs_.size(); k-- > 0;) {
    SensorPair& sp = sensorPairs_[k];
    const ShapeRecord& sensor = shapes_[static_cast<std::size_t>(sp.sensor)];
    const ShapeRecord& visitor = shapes_[static_cast<std::size_t>(sp.visitor)];
    const Body& sb = bodies_[static_cast<std::size_t>(sensor.body)];
    const Body& vb = bodies_[static_cast<std::size_t>(visitor.body)];
    if (!awake(sb) && !awake(vb)) continue;  // nothing moved
    const bool now = testOverlap(sensor.shape, sb.xf, visitor.shape, vb.xf);
    bool passed = false;
    if (!now && !sp.overlapping && awake(vb)) {
      // Not in it before or after: did the visitor's path cross it? (Its translation only;
      // the sensor at its end transform.)
      const Sweep sweep = stepSweep(vb);
      const Vec2 move = sweep.c2 - sweep.c1;
      if (move != Vec2{}) {
        const CastOutput cast = shapeCast(makeProxy(visitor.shape), sweepTransform(sweep, 0.0f),
                                          move, makeProxy(sensor.shape), sb.xf);
        passed = cast.hit;
      }
    }
    if (wantsSensorEvents(sp)) {
      if ((now && !sp.overlapping) || passed)
        sensorEvents_.begin.push_back({ref(sp.sensor), ref(sp.visitor), false});
      if ((!now && sp.overlapping) || passed)
        sensorEvents_.end.push_back({ref(sp.sensor), ref(sp.visitor), false});
    }
    sp.overlapping = now;
    if (!now && !overlaps(broadphase_.fatAABB(sensor.proxy), broadphase_.fatAABB(visitor.proxy)))
      destroySensorPair(k);
  }
}

}  // namespace rc
