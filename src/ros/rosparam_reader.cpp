#include "rosparam_reader.h"

#include <iomanip>
#include <limits>
#include <sstream>

#include <xmlrpcpp/XmlRpcValue.h>

namespace hex_slam {
namespace {

bool ToText(XmlRpc::XmlRpcValue& value, std::string* text) {
  switch (value.getType()) {
    case XmlRpc::XmlRpcValue::TypeBoolean:
      *text = static_cast<bool>(value) ? "true" : "false";
      return true;
    case XmlRpc::XmlRpcValue::TypeInt:
      *text = std::to_string(static_cast<int>(value));
      return true;
    case XmlRpc::XmlRpcValue::TypeDouble: {
      // Enough digits that the text parses back to the same double.
      std::ostringstream s;
      s << std::setprecision(std::numeric_limits<double>::max_digits10)
        << static_cast<double>(value);
      *text = s.str();
      return true;
    }
    case XmlRpc::XmlRpcValue::TypeString:
      *text = static_cast<std::string>(value);
      return true;
    default:
      return false;
  }
}

}  // namespace

PrivateParameters ReadPrivateParameters(const ros::NodeHandle& private_nh) {
  PrivateParameters result;
  const std::string prefix = private_nh.getNamespace() + "/";
  std::vector<std::string> names;
  if (!private_nh.getParamNames(names)) {
    result.error = "cannot list parameters (is the ROS master running?)";
    return result;
  }
  for (const std::string& name : names) {
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string key = name.substr(prefix.size());
    XmlRpc::XmlRpcValue value;
    std::string text;
    if (!private_nh.getParam(name, value) || !ToText(value, &text)) {
      result.non_scalar_keys.push_back(key);
      continue;
    }
    result.values[key] = text;
  }
  return result;
}

}  // namespace hex_slam
