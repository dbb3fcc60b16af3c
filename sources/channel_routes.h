// One table per node from the full channel names it reads to its typed
// channels (style rule 16): the node's HandlePacket(channel, bytes, receive
// time) looks the name up here, and its subscription list (InputChannels)
// is the table's names, so what a source delivers and what the node handles
// cannot disagree.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace birotor {

template <typename Channel>
class ChannelRoutes {
 public:
  // A row: the full name (prefix included) and the channel it means.
  void Add(std::string name, Channel channel) { rows_.push_back({std::move(name), channel}); }

  // The channel of a full name; false for a name not in the table. A linear
  // search: a node reads at most a handful of channels.
  bool Find(std::string_view name, Channel* channel) const {
    for (const Row& row : rows_) {
      if (row.name == name) {
        *channel = row.channel;
        return true;
      }
    }
    return false;
  }

  // Every name, in the order added: the list to subscribe a source to.
  std::vector<std::string> Names() const {
    std::vector<std::string> names;
    names.reserve(rows_.size());
    for (const Row& row : rows_) names.push_back(row.name);
    return names;
  }

 private:
  struct Row {
    std::string name;
    Channel channel;
  };
  std::vector<Row> rows_;
};

}  // namespace birotor
