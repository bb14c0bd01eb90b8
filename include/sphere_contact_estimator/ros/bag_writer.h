#pragma once

// STL
#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

// ROS
#include <ros/serialization.h>
#include <ros/time.h>
#include <rosbag/message_instance.h>

namespace sphere_contact_estimator
{
/// Writes a ROS bag (format 2.0, http://wiki.ros.org/Bags/Format/2.0, uncompressed chunks) with every record built in
/// memory and a chunk written at once. rosbag::Bag::write seeks to the end of the file and asks its position at
/// every message, several system calls each: bag_analyze's four writes per odometry message took 130 us on these
/// machines, thirteen times the whole analysis. This writer makes none between chunks. rosbag reads what it writes
/// (C++, Python, `rosbag info`; test_bag_analyze and replay.test read it back).
///
/// Messages keep their connection: the node's own topics one each (type, md5sum and definition of the message, as
/// rosbag writes them), a copied input message the connection it had in the input (its whole connection header:
/// caller id, latching). Throws std::runtime_error when the file cannot be written.
class BagWriter
{
public:
  explicit BagWriter(const std::string& path, std::size_t chunk_threshold = 768 * 1024);
  ~BagWriter();
  BagWriter(const BagWriter&) = delete;
  BagWriter& operator=(const BagWriter&) = delete;

  /// A message of the package's on `topic` at bag time `time`.
  template <class M>
  void write(const std::string& topic, const ros::Time& time, const M& message)
  {
    namespace mt = ros::message_traits;
    const std::uint32_t id = connection(topic, mt::datatype(message), mt::md5sum(message), mt::definition(message));
    const std::uint32_t size = ros::serialization::serializationLength(message);
    std::uint8_t* data = beginMessage(id, time, size);
    ros::serialization::OStream stream(data, size);
    ros::serialization::serialize(stream, message);
  }

  /// An input message, copied as it was (its bytes, its connection), at its own bag time and topic.
  void write(const rosbag::MessageInstance& message);
  /// The same under another time (and topic, when not empty).
  void write(const rosbag::MessageInstance& message, const ros::Time& time, const std::string& topic = {});

  /// Writes the open chunk, the index and the bag header. Called by the destructor; throws when writing fails.
  void close();
  bool isOpen() const { return file_ != nullptr; }

private:
  struct Connection
  {
    std::uint32_t id = 0;
    std::string topic;
    std::vector<std::pair<std::string, std::string>> header;  // the connection header's fields
  };
  struct ChunkInfo
  {
    std::uint64_t position = 0;
    ros::Time start, end;
    std::map<std::uint32_t, std::uint32_t> counts;  // per connection
  };

  // (the message traits' C strings: a message definition is kilobytes, copied only when the connection is new)
  std::uint32_t connection(const std::string& topic, const char* datatype, const char* md5sum, const char* definition);
  std::uint32_t connection(const rosbag::MessageInstance& message, const std::string& topic);
  std::uint32_t addConnection(const std::string& topic, std::vector<std::pair<std::string, std::string>> header);
  std::uint8_t* beginMessage(std::uint32_t connection, const ros::Time& time, std::uint32_t size);
  void closeChunk();
  void put(const void* data, std::size_t size);

  std::string path_;
  std::FILE* file_ = nullptr;
  std::size_t threshold_;
  bool pending_close_ = false;          // the open chunk is full: written before the next message
  std::uint64_t position_ = 0;          // bytes written to the file
  std::vector<std::uint8_t> chunk_;     // the open chunk's records
  std::vector<std::uint8_t> scratch_;   // records outside chunks
  ChunkInfo open_;                      // of the open chunk
  std::map<std::uint32_t, std::vector<std::pair<ros::Time, std::uint32_t>>> index_;  // of the open chunk
  std::vector<ChunkInfo> chunks_;
  std::vector<Connection> connections_;
  std::map<std::string, std::uint32_t> by_topic_;  // the package's own connections
  std::map<std::pair<const void*, std::string>, std::uint32_t> by_input_;  // input connections, by header and topic
};

}  // namespace sphere_contact_estimator
