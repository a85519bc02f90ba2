from coopdrive.geodesy.local_tangent_plane import LocalTangentPlane
from coopdrive.geodesy.origin import GeodeticOrigin

__all__ = ["GeodeticOrigin", "LocalTangentPlane"]
