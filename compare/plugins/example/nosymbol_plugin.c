// A shared module that is not an engine plugin: it lacks the pool_engine_plugin entry symbol.
// The tests check that pool-compare refuses it with a clear message.
int pool_engine_plugin_misspelt(void);
int pool_engine_plugin_misspelt(void) { return 1; }
