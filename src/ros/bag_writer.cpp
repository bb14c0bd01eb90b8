#include "sphere_contact_estimator/ros/bag_writer.h"

// STL
#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace sphere_contact_estimator
{
namespace
{
// record opcodes (format 2.0)
constexpr std::uint8_t kMessageData = 0x02, kBagHeader = 0x03, kIndexData = 0x04, kChunk = 0x05,
                       kChunkInfo = 0x06, kConnection = 0x07;
constexpr std::size_t kBagHeaderLength = 4096;  // the bag header record, padded, so that it can be rewritten in place
const char kMagic[] = "#ROSBAG V2.0\n";

// Little-endian fields into a byte buffer.
struct Out
{
  std::vector<std::uint8_t>& b;
  void bytes(const void* p, std::size_t n)
  {
    const auto* c = static_cast<const std::uint8_t*>(p);
    b.insert(b.end(), c, c + n);
  }
  void u32(std::uint32_t v)
  {
    const std::uint8_t c[4] = { static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8),
                                static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>(v >> 24) };
    bytes(c, 4);
  }
  void u64(std::uint64_t v)
  {
    u32(static_cast<std::uint32_t>(v));
    u32(static_cast<std::uint32_t>(v >> 32));
  }
  void time(const ros::Time& t)
  {
    u32(t.sec);
    u32(t.nsec);
  }
  // a header field: <length><name>=<value>
  void field(const char* name, const void* value, std::size_t size)
  {
    const std::size_t n = std::strlen(name);
    u32(static_cast<std::uint32_t>(n + 1 + size));
    bytes(name, n);
    b.push_back('=');
    bytes(value, size);
  }
  void field(const char* name, const std::string& value) { field(name, value.data(), value.size()); }
  void fieldU8(const char* name, std::uint8_t v) { field(name, &v, 1); }
  void fieldU32(const char* name, std::uint32_t v)
  {
    const std::uint8_t c[4] = { static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8),
                                static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>(v >> 24) };
    field(name, c, 4);
  }
  void fieldU64(const char* name, std::uint64_t v)
  {
    std::uint8_t c[8];
    for (int i = 0; i < 8; ++i)
      c[i] = static_cast<std::uint8_t>(v >> (8 * i));
    field(name, c, 8);
  }
  void fieldTime(const char* name, const ros::Time& t) { fieldU64(name, (std::uint64_t(t.nsec) << 32) | t.sec); }
  // a length placeholder at the current end, filled by patch()
  std::size_t hole()
  {
    u32(0);
    return b.size() - 4;
  }
  void patch(std::size_t at)
  {
    const std::uint32_t v = static_cast<std::uint32_t>(b.size() - at - 4);
    for (int i = 0; i < 4; ++i)
      b[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
  }
};

// A connection record: header <op, conn, topic>, data the connection header's fields.
void connectionRecord(std::vector<std::uint8_t>& buffer, std::uint32_t id, const std::string& topic,
                      const std::vector<std::pair<std::string, std::string>>& header)
{
  Out o{ buffer };
  const std::size_t h = o.hole();
  o.fieldU8("op", kConnection);
  o.fieldU32("conn", id);
  o.field("topic", topic);
  o.patch(h);
  const std::size_t d = o.hole();
  for (const auto& [name, value] : header)
    o.field(name.c_str(), value);
  o.patch(d);
}
}  // namespace

BagWriter::BagWriter(const std::string& path, std::size_t chunk_threshold) : path_(path), threshold_(chunk_threshold)
{
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_)
    throw std::runtime_error("cannot write bag " + path + ": " + std::strerror(errno));
  // the magic, and a bag header with no index yet (rewritten by close())
  put(kMagic, sizeof(kMagic) - 1);
  scratch_.clear();
  Out o{ scratch_ };
  const std::size_t h = o.hole();
  o.fieldU8("op", kBagHeader);
  o.fieldU64("index_pos", 0);
  o.fieldU32("conn_count", 0);
  o.fieldU32("chunk_count", 0);
  o.patch(h);
  const std::uint32_t padding = static_cast<std::uint32_t>(kBagHeaderLength - scratch_.size() - 4);
  o.u32(padding);
  scratch_.insert(scratch_.end(), padding, ' ');
  put(scratch_.data(), scratch_.size());
  chunk_.reserve(threshold_ + 64 * 1024);
}

BagWriter::~BagWriter()
{
  try
  {
    close();
  }
  catch (const std::exception&)  // a destructor must not throw; close() reports it to a caller that asks
  {
  }
}

void BagWriter::put(const void* data, std::size_t size)
{
  if (size && std::fwrite(data, 1, size, file_) != size)
    throw std::runtime_error("writing bag " + path_ + " failed: " + std::strerror(errno));
  position_ += size;
}

std::uint32_t BagWriter::addConnection(const std::string& topic, std::vector<std::pair<std::string, std::string>> header)
{
  Connection c;
  c.id = static_cast<std::uint32_t>(connections_.size());
  c.topic = topic;
  c.header = std::move(header);
  // rosbag writes a connection's record into the chunk where it first appears, and again in the index
  connectionRecord(chunk_, c.id, c.topic, c.header);
  connections_.push_back(std::move(c));
  return connections_.back().id;
}

std::uint32_t BagWriter::connection(const std::string& topic, const char* datatype, const char* md5sum,
                                    const char* definition)
{
  const auto it = by_topic_.find(topic);
  if (it != by_topic_.end())
    return it->second;
  // as rosbag::Bag::write manufactures it for a message without a connection header
  const std::uint32_t id = addConnection(
      topic, { { "topic", topic }, { "type", datatype }, { "md5sum", md5sum }, { "message_definition", definition } });
  by_topic_[topic] = id;
  return id;
}

std::uint32_t BagWriter::connection(const rosbag::MessageInstance& message, const std::string& topic)
{
  const boost::shared_ptr<const ros::M_string> header = message.getConnectionHeader();
  const auto key = std::make_pair(static_cast<const void*>(header.get()), topic);
  const auto it = by_input_.find(key);
  if (it != by_input_.end())
    return it->second;
  std::vector<std::pair<std::string, std::string>> fields;
  if (header)
    for (const auto& [name, value] : *header)
      fields.emplace_back(name, name == "topic" ? topic : value);
  if (!header || !header->count("topic"))
    fields.emplace_back("topic", topic);
  if (!header || !header->count("type"))
    fields.emplace_back("type", message.getDataType());
  if (!header || !header->count("md5sum"))
    fields.emplace_back("md5sum", message.getMD5Sum());
  if (!header || !header->count("message_definition"))
    fields.emplace_back("message_definition", message.getMessageDefinition());
  const std::uint32_t id = addConnection(topic, std::move(fields));
  by_input_[key] = id;
  return id;
}

std::uint8_t* BagWriter::beginMessage(std::uint32_t connection, const ros::Time& time, std::uint32_t size)
{
  if (!file_)
    throw std::runtime_error("bag " + path_ + " is closed");
  if (pending_close_)
    closeChunk();
  if (open_.counts.empty())
    open_.start = open_.end = time;
  open_.start = std::min(open_.start, time);
  open_.end = std::max(open_.end, time);
  ++open_.counts[connection];
  index_[connection].emplace_back(time, static_cast<std::uint32_t>(chunk_.size()));
  Out o{ chunk_ };
  const std::size_t h = o.hole();
  o.fieldU8("op", kMessageData);
  o.fieldU32("conn", connection);
  o.fieldTime("time", time);
  o.patch(h);
  o.u32(size);
  chunk_.resize(chunk_.size() + size);
  std::uint8_t* data = chunk_.data() + chunk_.size() - size;
  // the caller fills the data before its next call: a full chunk is written then, not now
  pending_close_ = chunk_.size() >= threshold_;
  return data;
}

void BagWriter::write(const rosbag::MessageInstance& message)
{
  write(message, message.getTime(), message.getTopic());
}

void BagWriter::write(const rosbag::MessageInstance& message, const ros::Time& time, const std::string& topic)
{
  const std::uint32_t id = connection(message, topic.empty() ? message.getTopic() : topic);
  const std::uint32_t size = message.size();
  std::uint8_t* data = beginMessage(id, time, size);
  ros::serialization::OStream stream(data, size);
  message.write(stream);
}

void BagWriter::closeChunk()
{
  if (open_.counts.empty())
    return;
  // the chunk record: <op, compression, size> and its records, then one index record per connection in it
  open_.position = position_;
  scratch_.clear();
  Out o{ scratch_ };
  const std::size_t h = o.hole();
  o.fieldU8("op", kChunk);
  o.field("compression", std::string("none"));
  o.fieldU32("size", static_cast<std::uint32_t>(chunk_.size()));
  o.patch(h);
  o.u32(static_cast<std::uint32_t>(chunk_.size()));
  put(scratch_.data(), scratch_.size());
  put(chunk_.data(), chunk_.size());
  scratch_.clear();
  for (const auto& [id, entries] : index_)
  {
    const std::size_t ih = o.hole();
    o.fieldU8("op", kIndexData);
    o.fieldU32("ver", 1);
    o.fieldU32("conn", id);
    o.fieldU32("count", static_cast<std::uint32_t>(entries.size()));
    o.patch(ih);
    o.u32(static_cast<std::uint32_t>(entries.size() * 12));
    for (const auto& [t, offset] : entries)
    {
      o.time(t);
      o.u32(offset);
    }
  }
  put(scratch_.data(), scratch_.size());
  chunks_.push_back(open_);
  open_ = ChunkInfo{};
  index_.clear();
  chunk_.clear();
  pending_close_ = false;
}

void BagWriter::close()
{
  if (!file_)
    return;
  closeChunk();
  // the index: every connection, then every chunk's info
  const std::uint64_t index_pos = position_;
  scratch_.clear();
  for (const Connection& c : connections_)
    connectionRecord(scratch_, c.id, c.topic, c.header);
  Out o{ scratch_ };
  for (const ChunkInfo& c : chunks_)
  {
    const std::size_t h = o.hole();
    o.fieldU8("op", kChunkInfo);
    o.fieldU32("ver", 1);
    o.fieldU64("chunk_pos", c.position);
    o.fieldTime("start_time", c.start);
    o.fieldTime("end_time", c.end);
    o.fieldU32("count", static_cast<std::uint32_t>(c.counts.size()));
    o.patch(h);
    o.u32(static_cast<std::uint32_t>(c.counts.size() * 8));
    for (const auto& [id, count] : c.counts)
    {
      o.u32(id);
      o.u32(count);
    }
  }
  put(scratch_.data(), scratch_.size());
  // the bag header again, now with the index's position and the counts
  scratch_.clear();
  const std::size_t h = o.hole();
  o.fieldU8("op", kBagHeader);
  o.fieldU64("index_pos", index_pos);
  o.fieldU32("conn_count", static_cast<std::uint32_t>(connections_.size()));
  o.fieldU32("chunk_count", static_cast<std::uint32_t>(chunks_.size()));
  o.patch(h);
  const std::uint32_t padding = static_cast<std::uint32_t>(kBagHeaderLength - scratch_.size() - 4);
  o.u32(padding);
  scratch_.insert(scratch_.end(), padding, ' ');
  std::FILE* f = file_;
  file_ = nullptr;
  const bool ok = std::fseek(f, static_cast<long>(sizeof(kMagic) - 1), SEEK_SET) == 0 &&
                  std::fwrite(scratch_.data(), 1, scratch_.size(), f) == scratch_.size();
  if (std::fclose(f) != 0 || !ok)
    throw std::runtime_error("writing bag " + path_ + " failed: " + std::strerror(errno));
}

}  // namespace sphere_contact_estimator
