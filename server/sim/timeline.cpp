#include "server/sim/timeline.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace flagsim::sim {
namespace {

/// The keys of one control's track around a position: `from` the last at or before it, `to`
/// the first after it, `before` the track's key before `from`, `after` its key after `to`;
/// -1 where there is none.
struct Around {
  int before = -1, from = -1, to = -1, after = -1;
};

template <class Sets>
Around FindAround(const std::vector<Keyframe>& keys, double position, Sets sets) {
  Around around;
  for (int i = 0; i < int(keys.size()); ++i) {
    if (!sets(keys[i])) continue;
    if (keys[i].time <= position) {
      around.before = around.from;
      around.from = i;
    } else if (around.to < 0) {
      around.to = i;
    } else {
      around.after = i;
      break;
    }
  }
  return around;
}

/// The segment from..to of a track for one scalar, read from each key by `value`; where the
/// track has no key before or after, the cubic reads the segment's own ends.
template <class Value>
Segment SegmentOf(const std::vector<Keyframe>& keys, const Around& a, Value value) {
  Segment g;
  g.t0 = g.t_before = keys[a.from].time;
  g.v0 = g.v_before = value(keys[a.from]);
  g.t1 = g.t_after = keys[a.to].time;
  g.v1 = g.v_after = value(keys[a.to]);
  if (a.before >= 0) {
    g.t_before = keys[a.before].time;
    g.v_before = value(keys[a.before]);
  }
  if (a.after >= 0) {
    g.t_after = keys[a.after].time;
    g.v_after = value(keys[a.after]);
  }
  return g;
}

/// One scalar on a track with at least one key: held before and after the track, else the law.
template <class Value>
double Scalar(const std::vector<Keyframe>& keys, const Around& a, double position, Value value) {
  if (a.from < 0) return value(keys[a.to]);
  if (a.to < 0) return value(keys[a.from]);
  return Interpolate(keys[a.from].law, SegmentOf(keys, a, value), position);
}

/// The turn from direction a to direction b (unit vectors) as a rotation about `axis`: its
/// angle times the cosine between its own axis and `axis` (0 if a and b are (anti)parallel).
double TurnAbout(const Vec3& a, const Vec3& b, const Vec3& axis) {
  const Vec3 normal = Cross(a, b);
  const double sine = Length(normal);
  if (sine < 1e-12) return 0;
  return std::atan2(sine, Dot(a, b)) * Dot(normal, axis) / sine;
}

Vec3 WindDirection(const Keyframe& key) { return Scaled(key.wind->velocity, 1 / Length(key.wind->velocity)); }
bool Blows(const Keyframe& key) { return Length(key.wind->velocity) > 0; }

/// How far the wind has turned at `position`, as a fraction of the turn from the `from` key's
/// direction to the `to` key's (both winds blowing): the law on the angle turned. The cubic's
/// rates come from the turns before and after, counted along this turn's axis: a wind that
/// turns on keeps its rate through the key, one that swings back slows to turn back.
double TurnFraction(const std::vector<Keyframe>& keys, const Around& a, double position) {
  const Vec3 from = WindDirection(keys[a.from]), to = WindDirection(keys[a.to]);
  const Vec3 normal = Cross(from, to);
  const double angle = std::atan2(Length(normal), Dot(from, to));
  if (angle < 1e-9) return 1.0;
  Segment g{keys[a.from].time, keys[a.to].time, 0, angle, keys[a.from].time, 0, keys[a.to].time, angle};
  if (Length(normal) > 1e-12) {  // opposite directions have no axis to count turns along
    const Vec3 axis = Scaled(normal, 1 / Length(normal));
    if (a.before >= 0 && Blows(keys[a.before])) {
      g.t_before = keys[a.before].time;
      g.v_before = -TurnAbout(WindDirection(keys[a.before]), from, axis);
    }
    if (a.after >= 0 && Blows(keys[a.after])) {
      g.t_after = keys[a.after].time;
      g.v_after = angle + TurnAbout(to, WindDirection(keys[a.after]), axis);
    }
  }
  return Interpolate(keys[a.from].law, g, position) / angle;
}

/// Speed `speed` in the direction a fraction w of the way from velocity `from` to `to` (a
/// velocity of zero takes the other's direction).
Vec3 Turned(const Vec3& from, const Vec3& to, double w, double speed) {
  const double from_speed = Length(from), to_speed = Length(to);
  if (from_speed == 0 && to_speed == 0) return {0, 0, 0};
  if (from_speed == 0) return Scaled(to, speed / to_speed);
  if (to_speed == 0) return Scaled(from, speed / from_speed);
  return Scaled(Slerp(Scaled(from, 1 / from_speed), Scaled(to, 1 / to_speed), w), speed);
}

WindControl WindAt(const std::vector<Keyframe>& keys, const Around& a, double position) {
  if (a.from < 0) return *keys[a.to].wind;
  if (a.to < 0) return *keys[a.from].wind;
  const auto speed = [](const Keyframe& key) { return Length(key.wind->velocity); };
  const auto gust = [](const Keyframe& key) { return key.wind->gust; };
  WindControl wind;
  wind.gust = std::max(0.0, Scalar(keys, a, position, gust));  // the cubic may overshoot below 0
  const Vec3 &from = keys[a.from].wind->velocity, &to = keys[a.to].wind->velocity;
  const double fraction = Blows(keys[a.from]) && Blows(keys[a.to]) ? TurnFraction(keys, a, position) : 1.0;
  wind.velocity = Turned(from, to, fraction, std::max(0.0, Scalar(keys, a, position, speed)));
  return wind;
}

CameraControl CameraAt(const std::vector<Keyframe>& keys, const Around& a, double position) {
  CameraControl camera;
  for (int k = 0; k < 3; ++k) {
    camera.eye[k] = Scalar(keys, a, position, [k](const Keyframe& key) { return key.camera->eye[k]; });
    camera.target[k] = Scalar(keys, a, position, [k](const Keyframe& key) { return key.camera->target[k]; });
  }
  camera.fov = Scalar(keys, a, position, [](const Keyframe& key) { return key.camera->fov; });
  return camera;
}

/// Every parameter name some key sets, sorted.
std::vector<std::string> ParameterNames(const std::vector<Keyframe>& keys) {
  std::vector<std::string> names;
  for (const Keyframe& key : keys) {
    for (const ParameterControl& parameter : key.parameters) names.push_back(parameter.name);
  }
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  return names;
}

const double* FindParameter(const std::vector<ParameterControl>& parameters, const std::string& name) {
  for (const ParameterControl& parameter : parameters) {
    if (parameter.name == name) return &parameter.value;
  }
  return nullptr;
}

/// v turned by `angle` (rad) about the unit vector `axis` (Rodrigues).
Vec3 Rotated(const Vec3& v, const Vec3& axis, double angle) {
  const Vec3 across = Cross(axis, v);
  const double along = Dot(axis, v) * (1 - std::cos(angle)), sine = std::sin(angle), cosine = std::cos(angle);
  return {v[0] * cosine + across[0] * sine + axis[0] * along,
          v[1] * cosine + across[1] * sine + axis[1] * along,
          v[2] * cosine + across[2] * sine + axis[2] * along};
}

/// The turn taking direction `a` to direction `b` (unit vectors): its unit axis and angle (rad).
/// Opposite directions turn about the vertical made perpendicular to `a` (x if `a` is vertical),
/// as Slerp does.
std::pair<Vec3, double> TurnBetween(const Vec3& a, const Vec3& b) {
  Vec3 axis = Cross(a, b);
  const double angle = std::atan2(Length(axis), Dot(a, b));
  if (Length(axis) < 1e-12) {
    const Vec3 up = std::abs(a[1]) < 0.9 ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
    const double on_a = Dot(up, a);
    axis = {up[0] - on_a * a[0], up[1] - on_a * a[1], up[2] - on_a * a[2]};
  }
  return {Scaled(axis, 1 / Length(axis)), angle};
}

/// The wind `now` with a part `left` of the jump from `start` to `from` added back: its speed
/// changed by left (|from| - |start|), its direction turned by left of the turn from start's
/// to from's.
WindControl WithJump(const WindControl& now, const WindControl& start, const WindControl& from, double left) {
  WindControl wind = now;
  wind.gust = std::max(0.0, now.gust + (from.gust - start.gust) * left);
  const double start_speed = Length(start.velocity), from_speed = Length(from.velocity);
  const double now_speed = Length(now.velocity);
  const double speed = std::max(0.0, now_speed + (from_speed - start_speed) * left);
  Vec3 direction = now_speed > 0 ? Scaled(now.velocity, 1 / now_speed) : Vec3{0, 0, 0};
  if (start_speed > 0 && from_speed > 0 && now_speed > 0) {
    const auto [axis, angle] =
        TurnBetween(Scaled(start.velocity, 1 / start_speed), Scaled(from.velocity, 1 / from_speed));
    direction = Rotated(direction, axis, angle * left);
  } else if (now_speed == 0 && from_speed > 0) {
    direction = Scaled(from.velocity, 1 / from_speed);  // dying down: the way it blew
  }
  wind.velocity = Scaled(direction, speed);
  return wind;
}

/// Adds back a part `left` of the jump from `start` to `from` to the controls `now`, control by
/// control; controls either lacks are left as they are.
void AddJump(const Controls& start, const Controls& from, double left, Controls* now) {
  if (now->wind && start.wind && from.wind) *now->wind = WithJump(*now->wind, *start.wind, *from.wind, left);
  for (ParameterControl& parameter : now->parameters) {
    const double* begun = FindParameter(start.parameters, parameter.name);
    const double* held = FindParameter(from.parameters, parameter.name);
    if (begun != nullptr && held != nullptr) parameter.value += (*held - *begun) * left;
  }
  if (now->camera && start.camera && from.camera) {
    for (int k = 0; k < 3; ++k) {
      now->camera->eye[k] += (from.camera->eye[k] - start.camera->eye[k]) * left;
      now->camera->target[k] += (from.camera->target[k] - start.camera->target[k]) * left;
    }
    now->camera->fov += (from.camera->fov - start.camera->fov) * left;
  }
}

}  // namespace

const double* Keyframe::Parameter(const std::string& name) const { return FindParameter(parameters, name); }

bool Timeline::Add(const Keyframe& key) {
  const auto at = std::lower_bound(keys_.begin(), keys_.end(), key.time,
                                   [](const Keyframe& each, double time) { return each.time < time; });
  if (at != keys_.end() && at->time == key.time) {
    *at = key;
    return true;
  }
  keys_.insert(at, key);
  return false;
}

bool Timeline::Remove(double time) {
  const auto at =
      std::find_if(keys_.begin(), keys_.end(), [time](const Keyframe& key) { return key.time == time; });
  if (at == keys_.end()) return false;
  keys_.erase(at);
  if (keys_.empty()) {
    Clear();  // back to 0, as after clear
  } else if (position_ > End()) {
    position_ = End();  // it stays on the timeline
  }
  return true;
}

void Timeline::Clear() {
  keys_.clear();
  glide_.reset();
  position_ = 0;
}

const Keyframe* Timeline::Find(double time) const {
  for (const Keyframe& key : keys_) {
    if (key.time == time) return &key;
  }
  return nullptr;
}

void Timeline::Seek(double position) {
  position_ = position;
  glide_.reset();
}

// (position, glide) => (position + speed dt, glide + dt), wrapped or stopped at the end
void Timeline::Advance(double dt) {
  if (!playing_ || keys_.empty()) return;
  const bool was_gliding = glide_.has_value();
  if (glide_ && (glide_->elapsed += dt) >= kGlideTime) glide_.reset();
  const double end = End();
  if (!loop_ && position_ >= end) {
    position_ = end;
    if (!was_gliding) playing_ = false;  // the step from the end has been taken at its values
    return;
  }
  position_ += speed_ * dt;
  if (loop_ && position_ >= end) {
    position_ = end > 0 ? std::fmod(position_, end) : 0.0;
  } else if (!loop_ && position_ > end) {
    position_ = end;
  }
}

int Timeline::SegmentAt(double position) const {
  return int(std::upper_bound(keys_.begin(), keys_.end(), position,
                              [](double time, const Keyframe& key) { return time < key.time; }) -
             keys_.begin());
}

// keys around the position, per control => each control by its law
Controls Timeline::Interpolated(double position) const {
  Controls controls;
  const Around wind = FindAround(keys_, position, [](const Keyframe& key) { return key.wind.has_value(); });
  if (wind.from >= 0 || wind.to >= 0) controls.wind = WindAt(keys_, wind, position);
  for (const std::string& name : ParameterNames(keys_)) {
    const auto value = [&name](const Keyframe& key) { return *key.Parameter(name); };
    const Around a =
        FindAround(keys_, position, [&name](const Keyframe& key) { return key.Parameter(name); });
    controls.parameters.push_back({name, Scalar(keys_, a, position, value)});
  }
  const Around camera =
      FindAround(keys_, position, [](const Keyframe& key) { return key.camera.has_value(); });
  if (camera.from >= 0 || camera.to >= 0) controls.camera = CameraAt(keys_, camera, position);
  return controls;
}

Controls Timeline::Evaluate(double position) const {
  Controls controls = Interpolated(position);
  if (glide_) {
    const Segment glide{0, kGlideTime, 1, 0, 0, 1, kGlideTime, 0};  // 1 - w, by the smooth law
    AddJump(glide_->start, glide_->from, Interpolate(ControlLaw::kSmooth, glide, glide_->elapsed), &controls);
  }
  return controls;
}

std::vector<ParameterRange> Timeline::ParameterRanges(double position) const {
  std::vector<ParameterRange> ranges;
  for (const std::string& name : ParameterNames(keys_)) {
    const auto value = [&name](const Keyframe& key) { return *key.Parameter(name); };
    const Around a =
        FindAround(keys_, position, [&name](const Keyframe& key) { return key.Parameter(name); });
    ParameterRange range{name, 0, 0};
    if (a.from < 0 || a.to < 0) {
      range.low = range.high = value(keys_[a.from < 0 ? a.to : a.from]);
    } else {
      const ValueRange reached = RangeOver(keys_[a.from].law, SegmentOf(keys_, a, value));
      range.low = reached.low;
      range.high = reached.high;
    }
    const double* begun = glide_ ? FindParameter(glide_->start.parameters, name) : nullptr;
    const double* held = glide_ ? FindParameter(glide_->from.parameters, name) : nullptr;
    if (begun != nullptr && held != nullptr) {  // the jump still to die away, at most all of it
      range.low += std::min(0.0, *held - *begun);
      range.high += std::max(0.0, *held - *begun);
    }
    ranges.push_back(range);
  }
  return ranges;
}

void Timeline::StartGlide(const Controls& from) { glide_ = Glide{0, from, Interpolated(position_)}; }

bool Timeline::operator==(const Timeline& other) const {
  const bool same_glide =
      glide_.has_value() == other.glide_.has_value() &&
      (!glide_ || (glide_->elapsed == other.glide_->elapsed && glide_->from == other.glide_->from &&
                   glide_->start == other.glide_->start));
  return keys_ == other.keys_ && playing_ == other.playing_ && position_ == other.position_ &&
         speed_ == other.speed_ && loop_ == other.loop_ && same_glide;
}

bool operator==(const WindControl& a, const WindControl& b) {
  return a.velocity == b.velocity && a.gust == b.gust;
}
bool operator==(const CameraControl& a, const CameraControl& b) {
  return a.eye == b.eye && a.target == b.target && a.fov == b.fov;
}
bool operator==(const ParameterControl& a, const ParameterControl& b) {
  return a.name == b.name && a.value == b.value;
}
bool operator==(const Controls& a, const Controls& b) {
  return a.wind == b.wind && a.parameters == b.parameters && a.camera == b.camera;
}
bool operator==(const Keyframe& a, const Keyframe& b) {
  return a.time == b.time && a.law == b.law && a.wind == b.wind && a.parameters == b.parameters &&
         a.camera == b.camera;
}

}  // namespace flagsim::sim
