from enum import StrEnum

class StageCameraSetKind(StrEnum):
    STAGE_CAMERA = "stage_camera"

    def __str__(self) -> str:
        return str(self.value)
