/* The OpenMM classes this plugin's wrappers refer to, declared just enough for SWIG. Imported (not included)
 * with module="openmm", so the generated proxies subclass openmm.Force / openmm.Integrator and share the type
 * table of Debian's openmm module (same SWIG 4.1 runtime); Debian does not ship OpenMM's own .i files. */
%module openmm

namespace OpenMM {
class Force {
public:
    virtual ~Force();
};
class Integrator {
public:
    virtual ~Integrator();
};
class Context {
};
class System {
};
}
