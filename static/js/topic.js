// A list of listeners: a module announces something (a job to view, new measurements), the
// modules that import it listen, and so no two modules need to import each other.

/** A topic: `on(listener)` adds a listener, `emit(...args)` calls each in the order added. */
export function topic() {
  const listeners = [];
  return {
    on: (listener) => { listeners.push(listener); },
    emit: (...args) => { for (const listener of listeners) listener(...args); },
  };
}
