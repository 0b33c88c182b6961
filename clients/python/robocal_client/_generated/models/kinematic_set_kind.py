from enum import StrEnum

class KinematicSetKind(StrEnum):
    KINEMATIC = "kinematic"

    def __str__(self) -> str:
        return str(self.value)
