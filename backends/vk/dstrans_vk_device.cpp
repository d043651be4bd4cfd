// Implements dstrans_vk_device.hpp.
#include "dstrans_vk_device.hpp"

#include <cstring>

namespace dstrans::vk {

namespace {
VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                          VkDebugUtilsMessageTypeFlagsEXT,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT)
    static_cast<std::vector<std::string>*>(user)->push_back(data->pMessage ? data->pMessage : "(no message)");
  return VK_FALSE;
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

result<std::unique_ptr<headless_device>> headless_device::create(bool validation) {
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

  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "dstrans";
  app.apiVersion = VK_API_VERSION_1_3;
  const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
  VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ici.pNext = validation ? &messenger : nullptr;  // also reports instance creation itself
  ici.pApplicationInfo = &app;
  ici.enabledLayerCount = validation ? 1u : 0u;
  ici.ppEnabledLayerNames = &layer;
  ici.enabledExtensionCount = 1;
  ici.ppEnabledExtensionNames = extensions;
  const VkResult created = vkCreateInstance(&ici, nullptr, &hd->ctx_.instance);
  if (created == VK_ERROR_INCOMPATIBLE_DRIVER)
    return failure{"no Vulkan driver is installed (Debian: mesa-vulkan-drivers for lavapipe)"};
  if (created != VK_SUCCESS)
    return failure{"cannot create a Vulkan 1.3 instance (VkResult " + std::to_string(int(created)) + ")"};
  hd->ctx_.debug_utils = true;
  if (validation) {
    auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(hd->ctx_.instance, "vkCreateDebugUtilsMessengerEXT"));
    if (create_messenger) create_messenger(hd->ctx_.instance, &messenger, nullptr, &hd->messenger_);
  }

  std::uint32_t count = 0;
  vkEnumeratePhysicalDevices(hd->ctx_.instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(hd->ctx_.instance, &count, devices.data());
  for (VkPhysicalDevice pd : devices) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(pd, &props);
    if (props.apiVersion < VK_API_VERSION_1_3) continue;
    std::uint32_t nq = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &nq, nullptr);
    std::vector<VkQueueFamilyProperties> families(nq);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &nq, families.data());
    for (std::uint32_t q = 0; q < nq; ++q) {
      const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
      if ((families[q].queueFlags & need) == need && families[q].timestampValidBits > 0) {
        hd->ctx_.physical_device = pd;
        hd->ctx_.queue_family = q;
        break;
      }
    }
    if (hd->ctx_.physical_device) break;
  }
  if (!hd->ctx_.physical_device)
    return failure{"no Vulkan 1.3 device with a graphics and compute queue (Debian: mesa-vulkan-drivers for lavapipe)"};

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

std::vector<std::string> headless_device::validation_messages() {
  std::vector<std::string> out;
  out.swap(messages_);
  return out;
}

}  // namespace dstrans::vk
