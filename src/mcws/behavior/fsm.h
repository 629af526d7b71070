#pragma once
/// \file
/// \brief A small, data-driven finite state machine M = {Q, Sigma, delta, q0, F}.
///
/// The engine of the combined behaviours of Wang et al. 2018 (section 2.2, eq. (3)), with no
/// robot knowledge: states and events are names, delta(q, sigma) = q' is a table, and the caller
/// feeds events. Built from a combined behaviour by mcws::stateMachineOf() (behavior_model.h), or
/// by hand:
/// \code
/// mcws::StateMachine m("door");
/// m.addState("closed");
/// m.addState("open");
/// m.addTransition("closed", "push", "open");
/// m.addTransition("open", "pull", "closed");
/// m.setInitial("closed");          // the machine is now in q0 = closed
/// m.addFinal("closed");
/// m.fire("pull");                  // nothing: no transition on "pull" from "closed"
/// m.fire("push").fired;            // true: now in "open"
/// \endcode
/// A hierarchical machine is just another StateMachine whose states stand for sub-machines
/// (superstates); the caller runs the sub-machine while its superstate is current and fires the
/// superstate's event when the sub-machine completes (inFinal() after at least one step).

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mcws {

/// \brief How StateMachine::toDot() draws a machine.
struct DotOptions {
  bool mark_current{false};   ///< fill the current state
  std::string rankdir{"LR"};  ///< Graphviz rankdir: LR, TB, ...
  /// Emit `subgraph "cluster_<name>" { ... }` instead of a `digraph`, with every node name
  /// prefixed by `<name>/`, so that the text can be pasted into a larger graph (a superstate's
  /// sub-machine drawn inside it).
  bool as_cluster{false};
};

/// \brief A deterministic finite state machine over named states and events.
///
/// Configuration mistakes (a duplicate state, a transition from an unknown state, two
/// transitions on one event from one state) throw mcws::Error naming the machine and the item.
/// Firing an event without a transition from the current state is an expected outcome: nothing
/// happens and fire() says so.
class StateMachine {
 public:
  /// \brief delta(from, event) = to, by indices into states() and events().
  struct Transition {
    std::size_t from{0};
    std::size_t event{0};
    std::size_t to{0};
    std::string label;  ///< drawn on the edge by toDot(); the event's name when empty
  };

  /// \brief What fire() did.
  struct Firing {
    bool fired{false};          ///< a transition happened
    std::size_t transition{0};  ///< its index in transitions() (when fired)
    explicit operator bool() const { return fired; }
  };

  /// \param name the machine's name, used in messages and as the DOT graph's name.
  explicit StateMachine(std::string name = "fsm");

  /// \brief Adds a state to Q. \return its index.
  /// \throws mcws::Error for an empty name or a state already in Q.
  std::size_t addState(const std::string& state);

  /// \brief Adds an event to Sigma (nothing when it is already there). \return its index.
  /// \throws mcws::Error for an empty name.
  std::size_t addEvent(const std::string& event);

  /// \brief Adds delta(from, event) = to; the event joins Sigma if new. \return its index.
  /// \param label text drawn on the edge by toDot() (e.g. the behaviour run in `from`).
  /// \throws mcws::Error when `from` or `to` is not in Q, or `from` already has a transition on
  ///   `event` (the machine would not be deterministic).
  std::size_t addTransition(const std::string& from, const std::string& event,
                            const std::string& to, std::string label = {});

  /// \brief Sets q0 and puts the machine there (as reset()).
  /// \throws mcws::Error when the state is not in Q.
  void setInitial(const std::string& state);

  /// \brief Adds a state to F. \throws mcws::Error when the state is not in Q.
  void addFinal(const std::string& state);

  /// \brief Sets a state's text in toDot() (default: its name). \throws as addFinal().
  void setStateLabel(const std::string& state, std::string label);

  /// \brief Back to q0: entry counts cleared, q0 entered once, steps() zero.
  /// \throws mcws::Error when there is no initial state.
  void reset();

  /// \brief Puts the machine in `state` without a transition, as an entry (entries + 1, steps()
  ///   unchanged): resuming a machine part-way, e.g. CB3 from q4 on the way back to the start.
  /// \throws mcws::Error when the state is not in Q or there is no initial state.
  void jumpTo(const std::string& state);

  /// \brief Feeds one event: fires delta(current, event) when it exists.
  /// \return whether a transition happened and which. An event without a transition from the
  ///   current state, or not in Sigma at all, changes nothing (fired = false).
  /// \throws mcws::Error when there is no initial state (the machine is in no state).
  Firing fire(const std::string& event);

  /// \brief delta(state, event) without firing; nullopt when undefined.
  std::optional<std::string> next(const std::string& state, const std::string& event) const;

  /// \brief Events with a transition from the current state, in the order of transitions().
  std::vector<std::string> enabledEvents() const;

  const std::string& name() const { return name_; }
  /// \brief The current state. \throws mcws::Error when there is no initial state.
  const std::string& current() const;
  std::size_t currentIndex() const;
  /// \brief Whether the current state is in F.
  bool inFinal() const;
  /// \brief Times `state` was entered since the last reset() (q0 counts once at reset; a
  ///   self-loop counts again). \throws mcws::Error when the state is not in Q.
  int entries(const std::string& state) const;
  /// \brief Transitions fired since the last reset().
  std::size_t steps() const { return steps_; }

  const std::vector<std::string>& states() const { return states_; }
  const std::vector<std::string>& events() const { return events_; }
  const std::vector<Transition>& transitions() const { return transitions_; }
  std::optional<std::string> initial() const;
  std::vector<std::string> finals() const;
  bool hasState(const std::string& state) const { return state_index_.count(state) != 0; }
  bool isFinal(const std::string& state) const;
  /// \brief Index of a state in states(). \throws mcws::Error when it is not in Q.
  std::size_t stateIndex(const std::string& state) const;

  /// \brief Graphviz DOT text of the machine: one node per state (F drawn as double circles,
  ///   q0 marked by an arrow from a point), one edge per transition labelled with its label
  ///   (or its event). Render with `dot -Tpng`.
  std::string toDot(const DotOptions& options = {}) const;

 private:
  void requireStarted() const;

  std::string name_;
  std::vector<std::string> states_, events_, state_labels_;
  std::map<std::string, std::size_t> state_index_, event_index_;
  std::vector<Transition> transitions_;
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> delta_;  // (from, event) -> index
  std::vector<bool> final_;
  std::optional<std::size_t> initial_, current_;
  std::vector<int> entries_;
  std::size_t steps_{0};
};

}  // namespace mcws
