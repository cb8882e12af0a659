#include "game/bots/memory.h"

#include <algorithm>

namespace game {

float confidence(const MemoryEntry& entry, std::int64_t now) {
  if (entry.actor < 0) return 0.0f;
  const std::int64_t fade = entry.sense == Sense::seen ? kSeenFadeTicks : kHeardFadeTicks;
  const std::int64_t age = now - entry.tick;
  if (age >= fade) return 0.0f;
  return entry.strength * (1.0f - static_cast<float>(age) / static_cast<float>(fade));
}

void remember(BotMind& mind, const Perception& p, std::int64_t now) {
  MemoryEntry* slot = nullptr;
  for (MemoryEntry& e : mind.memory)
    if (e.actor == p.actor) slot = &e;
  if (slot != nullptr) {
    if (p.strength < confidence(*slot, now)) return;  // it knows better already
  } else {
    float weakest = 0.0f;
    for (MemoryEntry& e : mind.memory) {
      const float c = confidence(e, now);
      if (slot == nullptr || c < weakest) {
        slot = &e;
        weakest = c;
      }
    }
  }
  slot->actor = p.actor;
  slot->sense = p.sense;
  slot->position = p.position;
  slot->velocity = p.sense == Sense::seen ? p.velocity : rc::Vec2{};
  slot->tick = now;
  slot->strength = p.strength;
}

void forgetFaded(BotMind& mind, std::int64_t now) {
  for (MemoryEntry& e : mind.memory)
    if (e.actor >= 0 && confidence(e, now) <= 0.0f) e = MemoryEntry{};
}

std::int32_t strongestMemory(const BotMind& mind, std::int64_t now) {
  std::int32_t best = -1;
  float bestConfidence = 0.0f;
  for (std::size_t k = 0; k < mind.memory.size(); ++k) {
    const float c = confidence(mind.memory[k], now);
    if (c > bestConfidence) {
      best = static_cast<std::int32_t>(k);
      bestConfidence = c;
    }
  }
  return best;
}

bool inSight(const BotMind& mind, const MemoryEntry& entry) {
  return entry.actor >= 0 && entry.sense == Sense::seen && entry.tick == mind.lastLook;
}

rc::Vec2 expectedPosition(const MemoryEntry& entry, std::int64_t now, std::int64_t horizon) {
  const std::int64_t age = std::clamp<std::int64_t>(now - entry.tick, 0, horizon);
  return entry.position + (static_cast<float>(age) * kTickSeconds) * entry.velocity;
}

}  // namespace game
