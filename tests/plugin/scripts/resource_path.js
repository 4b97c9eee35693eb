// Prints core.resourcePath() for the resource path checks.
print("resources: " + core.resourcePath());
