#include "mcws/behavior/fsm.h"

#include <sstream>

#include "mcws/core/error.h"

namespace mcws {
namespace {

/// A DOT double-quoted string: quotes and backslashes escaped, line breaks as \n.
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else {
      out += c;
    }
  }
  return out + "\"";
}

}  // namespace

StateMachine::StateMachine(std::string name) : name_(std::move(name)) {}

std::size_t StateMachine::addState(const std::string& state) {
  if (state.empty()) throw Error("state machine '" + name_ + "': a state needs a name");
  if (state_index_.count(state)) {
    throw Error("state machine '" + name_ + "': state '" + state + "' added twice");
  }
  state_index_[state] = states_.size();
  states_.push_back(state);
  state_labels_.push_back(state);
  final_.push_back(false);
  entries_.push_back(0);
  return states_.size() - 1;
}

std::size_t StateMachine::addEvent(const std::string& event) {
  if (event.empty()) throw Error("state machine '" + name_ + "': an event needs a name");
  const auto it = event_index_.find(event);
  if (it != event_index_.end()) return it->second;
  event_index_[event] = events_.size();
  events_.push_back(event);
  return events_.size() - 1;
}

std::size_t StateMachine::stateIndex(const std::string& state) const {
  const auto it = state_index_.find(state);
  if (it == state_index_.end()) {
    throw Error("state machine '" + name_ + "': '" + state + "' is not a state");
  }
  return it->second;
}

std::size_t StateMachine::addTransition(const std::string& from, const std::string& event,
                                        const std::string& to, std::string label) {
  const std::size_t f = stateIndex(from), t = stateIndex(to);
  const std::size_t e = addEvent(event);
  const auto key = std::make_pair(f, e);
  if (const auto it = delta_.find(key); it != delta_.end()) {
    throw Error("state machine '" + name_ + "': state '" + from +
                "' already has a transition on '" + event + "' (to '" +
                states_[transitions_[it->second].to] + "')");
  }
  delta_[key] = transitions_.size();
  transitions_.push_back({f, e, t, std::move(label)});
  return transitions_.size() - 1;
}

void StateMachine::setInitial(const std::string& state) {
  initial_ = stateIndex(state);
  reset();
}

void StateMachine::addFinal(const std::string& state) { final_[stateIndex(state)] = true; }

void StateMachine::setStateLabel(const std::string& state, std::string label) {
  state_labels_[stateIndex(state)] = std::move(label);
}

void StateMachine::reset() {
  if (!initial_) throw Error("state machine '" + name_ + "': no initial state");
  current_ = initial_;
  entries_.assign(states_.size(), 0);
  entries_[*initial_] = 1;
  steps_ = 0;
}

void StateMachine::requireStarted() const {
  if (!current_) throw Error("state machine '" + name_ + "': no initial state");
}

void StateMachine::jumpTo(const std::string& state) {
  requireStarted();
  current_ = stateIndex(state);
  ++entries_[*current_];
}

StateMachine::Firing StateMachine::fire(const std::string& event) {
  requireStarted();
  const auto e = event_index_.find(event);
  if (e == event_index_.end()) return {};
  const auto it = delta_.find({*current_, e->second});
  if (it == delta_.end()) return {};
  current_ = transitions_[it->second].to;
  ++entries_[*current_];
  ++steps_;
  return {true, it->second};
}

std::optional<std::string> StateMachine::next(const std::string& state,
                                              const std::string& event) const {
  const auto e = event_index_.find(event);
  if (e == event_index_.end()) return std::nullopt;
  const auto it = delta_.find({stateIndex(state), e->second});
  if (it == delta_.end()) return std::nullopt;
  return states_[transitions_[it->second].to];
}

std::vector<std::string> StateMachine::enabledEvents() const {
  requireStarted();
  std::vector<std::string> out;
  for (const Transition& t : transitions_) {
    if (t.from == *current_) out.push_back(events_[t.event]);
  }
  return out;
}

const std::string& StateMachine::current() const {
  requireStarted();
  return states_[*current_];
}

std::size_t StateMachine::currentIndex() const {
  requireStarted();
  return *current_;
}

bool StateMachine::inFinal() const {
  requireStarted();
  return final_[*current_];
}

int StateMachine::entries(const std::string& state) const { return entries_[stateIndex(state)]; }

std::optional<std::string> StateMachine::initial() const {
  if (!initial_) return std::nullopt;
  return states_[*initial_];
}

std::vector<std::string> StateMachine::finals() const {
  std::vector<std::string> out;
  for (std::size_t s = 0; s < states_.size(); ++s) {
    if (final_[s]) out.push_back(states_[s]);
  }
  return out;
}

bool StateMachine::isFinal(const std::string& state) const { return final_[stateIndex(state)]; }

std::string StateMachine::toDot(const DotOptions& options) const {
  const std::string prefix = options.as_cluster ? name_ + "/" : "";
  const auto node = [&](const std::string& state) { return quoted(prefix + state); };
  const std::string start = quoted(prefix + "__start");
  std::ostringstream dot;
  const std::string indent = "  ";
  if (options.as_cluster) {
    dot << "subgraph " << quoted("cluster_" + name_) << " {\n"
        << indent << "label=" << quoted(name_) << ";\n";
  } else {
    dot << "digraph " << quoted(name_) << " {\n"
        << indent << "rankdir=" << options.rankdir << ";\n";
  }
  dot << indent << "node [shape=circle];\n";
  if (initial_) dot << indent << start << " [shape=point, label=\"\"];\n";
  for (std::size_t s = 0; s < states_.size(); ++s) {
    dot << indent << node(states_[s]) << " [label=" << quoted(state_labels_[s]);
    if (final_[s]) dot << ", shape=doublecircle";
    if (options.mark_current && current_ && *current_ == s) dot << ", style=filled";
    dot << "];\n";
  }
  if (initial_) dot << indent << start << " -> " << node(states_[*initial_]) << ";\n";
  for (const Transition& t : transitions_) {
    dot << indent << node(states_[t.from]) << " -> " << node(states_[t.to])
        << " [label=" << quoted(t.label.empty() ? events_[t.event] : t.label) << "];\n";
  }
  dot << "}\n";
  return dot.str();
}

}  // namespace mcws
