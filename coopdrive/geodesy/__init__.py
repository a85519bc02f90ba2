from coopdrive.geodesy.local_tangent_plane import LocalTangentPlane

__all__ = ["LocalTangentPlane"]
