// Implements dstrans_vk_device.hpp.
#include "dstrans_vk_device.hpp"

#include <cstring>
#include <optional>

namespace dstrans::vk {

namespace {
VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                          VkDebugUtilsMessageTypeFlagsEXT,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT)
    static_cast<std::vector<std::string>*>(user)->push_back(data->pMessage ? data->pMessage : "(no message)");
  return VK_FALSE;
}

// deviceName, the kind of device and the driver, as headless_device::devices() lists them.
std::string driver_of(VkPhysicalDevice pd) {
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props.pNext = &driver;
  vkGetPhysicalDeviceProperties2(pd, &props);
  return std::string(driver.driverName) + " " + driver.driverInfo;
}
std::string describe(VkPhysicalDevice pd, std::size_t index) {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(pd, &props);
  const char* kind = props.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU     ? "discrete GPU"
                     : props.deviceType == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU ? "integrated GPU"
                     : props.deviceType == VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU    ? "virtual GPU"
                     : props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU            ? "cpu"
                                                                                   : "other";
  return std::to_string(index) + ": " + props.deviceName + ", " + kind + ", " + driver_of(pd);
}

// The queue family of `pd` with graphics, compute and timestamps, if pd offers Vulkan 1.3 and one.
std::optional<std::uint32_t> serving_queue(VkPhysicalDevice pd) {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(pd, &props);
  if (props.apiVersion < VK_API_VERSION_1_3) return std::nullopt;
  std::uint32_t nq = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &nq, nullptr);
  std::vector<VkQueueFamilyProperties> families(nq);
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &nq, families.data());
  const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  for (std::uint32_t q = 0; q < nq; ++q)
    if ((families[q].queueFlags & need) == need && families[q].timestampValidBits > 0) return q;
  return std::nullopt;
}

std::vector<VkPhysicalDevice> physical_devices(VkInstance instance) {
  std::uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance, &count, devices.data());
  return devices;
}

// The devices `selector` names (headless_device::create), or why none.
result<std::vector<VkPhysicalDevice>> chosen(const std::vector<VkPhysicalDevice>& all, const std::string& selector) {
  if (selector.empty()) return all;
  const bool index = selector.find_first_not_of("0123456789") == std::string::npos;
  std::string listed;
  for (std::size_t i = 0; i < all.size(); ++i) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(all[i], &props);
    if (index ? selector == std::to_string(i) : std::strstr(props.deviceName, selector.c_str()) != nullptr)
      return std::vector<VkPhysicalDevice>{all[i]};
    listed += "\n  " + describe(all[i], i);
  }
  return failure{"no Vulkan device " + std::string(index ? "number " : "named ") + "'" + selector + "'; the devices are:" +
                 (listed.empty() ? std::string(" none") : listed)};
}

// A Vulkan 1.3 instance with debug utils and, given `validation`, the Khronos layer reporting to it.
result<bool> make_instance(const VkDebugUtilsMessengerCreateInfoEXT* validation, VkInstance& instance) {
  const char* layer = "VK_LAYER_KHRONOS_validation";
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "dstrans";
  app.apiVersion = VK_API_VERSION_1_3;
  const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
  VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ici.pNext = validation;
  ici.pApplicationInfo = &app;
  ici.enabledLayerCount = validation ? 1u : 0u;
  ici.ppEnabledLayerNames = &layer;
  ici.enabledExtensionCount = 1;
  ici.ppEnabledExtensionNames = extensions;
  const VkResult created = vkCreateInstance(&ici, nullptr, &instance);
  if (created == VK_ERROR_INCOMPATIBLE_DRIVER)
    return failure{"no Vulkan driver is installed (Debian: mesa-vulkan-drivers for lavapipe)"};
  if (created != VK_SUCCESS)
    return failure{"cannot create a Vulkan 1.3 instance (VkResult " + std::to_string(int(created)) + ")"};
  return true;
}

bool has_layer(const char* name) {
  std::uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());
  for (const auto& l : layers)
    if (std::strcmp(l.layerName, name) == 0) return true;
  return false;
}
}  // namespace

result<std::unique_ptr<headless_device>> headless_device::create(bool validation, const std::string& device) {
  const char* layer = "VK_LAYER_KHRONOS_validation";
  if (validation && !has_layer(layer))
    return failure{"the Khronos validation layer is not installed (Debian: vulkan-validationlayers)"};
  std::unique_ptr<headless_device> hd(new headless_device);
  VkDebugUtilsMessengerCreateInfoEXT messenger{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messenger.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                          VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger.pfnUserCallback = on_message;
  messenger.pUserData = &hd->messages_;

  // The messenger also reports instance creation itself.
  if (auto made = make_instance(validation ? &messenger : nullptr, hd->ctx_.instance); !made) return failure{made.error()};
  hd->ctx_.debug_utils = true;
  if (validation) {
    auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(hd->ctx_.instance, "vkCreateDebugUtilsMessengerEXT"));
    if (create_messenger) create_messenger(hd->ctx_.instance, &messenger, nullptr, &hd->messenger_);
  }

  const auto candidates = chosen(physical_devices(hd->ctx_.instance), device);
  if (!candidates) return failure{candidates.error()};
  for (VkPhysicalDevice pd : *candidates)
    if (const std::optional<std::uint32_t> q = serving_queue(pd)) {
      hd->ctx_.physical_device = pd;
      hd->ctx_.queue_family = *q;
      break;
    }
  if (!hd->ctx_.physical_device)
    return failure{device.empty() ? "no Vulkan 1.3 device with a graphics and compute queue (Debian: mesa-vulkan-drivers for lavapipe)"
                                  : "Vulkan device '" + device + "' has no Vulkan 1.3 or no graphics and compute queue with timestamps"};

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qci.queueFamilyIndex = hd->ctx_.queue_family;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  v13.dynamicRendering = VK_TRUE;
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  features.pNext = &v13;
  features.features.fragmentStoresAndAtomics = VK_TRUE;
  features.features.depthClamp = VK_TRUE;  // light volumes cut by the near plane
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  dci.pNext = &features;
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  if (vkCreateDevice(hd->ctx_.physical_device, &dci, nullptr, &hd->ctx_.device) != VK_SUCCESS)
    return failure{"cannot create a Vulkan device with dynamic rendering"};
  vkGetDeviceQueue(hd->ctx_.device, hd->ctx_.queue_family, 0, &hd->ctx_.queue);
  return hd;
}

headless_device::~headless_device() {
  if (ctx_.device) vkDestroyDevice(ctx_.device, nullptr);
  if (messenger_) {
    auto destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(ctx_.instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy_messenger) destroy_messenger(ctx_.instance, messenger_, nullptr);
  }
  if (ctx_.instance) vkDestroyInstance(ctx_.instance, nullptr);
}

std::string headless_device::name() const {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(ctx_.physical_device, &props);
  return props.deviceName;
}

std::string headless_device::driver() const { return driver_of(ctx_.physical_device); }

result<std::vector<std::string>> headless_device::devices() {
  VkInstance instance = VK_NULL_HANDLE;
  if (auto made = make_instance(nullptr, instance); !made) return failure{made.error()};
  const std::vector<VkPhysicalDevice> all = physical_devices(instance);
  std::vector<std::string> out;
  for (std::size_t i = 0; i < all.size(); ++i) out.push_back(describe(all[i], i));
  vkDestroyInstance(instance, nullptr);
  return out;
}

std::vector<std::string> headless_device::validation_messages() {
  std::vector<std::string> out;
  out.swap(messages_);
  return out;
}

}  // namespace dstrans::vk
